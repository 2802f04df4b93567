#include "devices/test_suite_server.h"

#include "bus/frame_shapes.h"
#include "dialects/modbus_frames.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::sim {
namespace {

Frame read_write_request(std::uint8_t station, std::uint16_t read_start, std::uint16_t read_count,
                         std::uint16_t write_start, const WordList& words) {
  Frame f = modbus_read(station, fc::kReadWriteMultiple, read_start, read_count);
  f.write_start = write_start;
  f.write_count = static_cast<std::uint16_t>(words.size());
  f.words = words;
  f.byte_count = static_cast<std::uint8_t>(2 * words.size());
  return f;
}

}  // namespace

TestSuiteServer::TestSuiteServer(std::uint8_t station) : ModbusDevice(station) {
  for (std::uint16_t i = 0; i < kRegisters; ++i)
    registers_[i] = static_cast<std::uint16_t>(0x1000 + 0x111 * i);
}

DeviceLabel TestSuiteServer::label() const {
  return {"test_server", {}, {}, {}, std::string(kName)};
}

// A station next to the server's that is never on the bus.
std::uint8_t TestSuiteServer::absent_station() const {
  return static_cast<std::uint8_t>(station() == fc::kLastModbusStation ? station() - 1
                                                                       : station() + 1);
}

// Every round runs the suite's checks again with other values; the second also asks the
// absent station.
std::vector<Frame> TestSuiteServer::requests(unsigned round) const {
  const std::uint8_t s = station();
  const auto v = static_cast<std::uint16_t>(0x0100 * (round + 1));
  std::vector<Frame> out{
      report_server_id(s),
      modbus_read(s, fc::kGslReadHolding, 0, 4),
      read_write_request(s, 0, 4, 4, WordList{v, static_cast<std::uint16_t>(v + 1)}),
      write_single_register(s, 8, static_cast<std::uint16_t>(v + 2)),
      write_multiple_registers(
          s, 10, WordList{static_cast<std::uint16_t>(v + 3), static_cast<std::uint16_t>(v + 4)}),
      write_single_coil(s, 0, round % 2 == 0),
  };
  if (round == 1) out.push_back(modbus_read(absent_station(), fc::kGslReadHolding, 0, 2));
  // A read to address 0, which the specification does not allow: no station answers it.
  if (round == 2) out.push_back(modbus_read(fc::kModbusBroadcast, fc::kGslReadHolding, 0, 2));
  if (round == 3) {
    // Three registers in a byte count of 4 with 4 bytes, then in a byte count of 0 with 6.
    Frame mismatch = write_multiple_registers(s, 12, WordList{v, v});
    mismatch.count = 3;
    out.push_back(mismatch);
    Frame lying = write_multiple_registers(s, 12, WordList{v, v, v});
    lying.byte_count = 0;
    out.push_back(lying);
  }
  // A user-defined function the server lacks, station and code alone.
  if (round == 4) out.push_back(modbus_request(s, kUserDefined));
  return out;
}

ModbusDevice::Answer TestSuiteServer::answer_of(const Frame& request) const {
  if (request.station == fc::kModbusBroadcast) return Answer::Broadcast;
  if (fc::is_user_defined_function(request.function)) return Answer::Refused;
  if (request.function == fc::kGslWriteMultiple &&
      request.byte_count != 2 * request.count.value_or(0)) {
    return Answer::Refused;
  }
  return request.station == absent_station() ? Answer::LateFromAbsent : Answer::Normal;
}

WordList TestSuiteServer::read(std::uint16_t start, std::uint16_t count) const {
  WordList out;
  for (unsigned a = start; a < unsigned{start} + count; ++a)
    out.push_back(a < kRegisters ? registers_[a] : 0);
  return out;
}

void TestSuiteServer::write(std::uint16_t start, const WordList& words) {
  for (std::size_t i = 0; i < words.size(); ++i)
    if (start + i < kRegisters) registers_[start + i] = words[i];
}

BusEvent TestSuiteServer::reply(const Frame& request, Micros /*request_end*/) {
  const std::uint16_t start = request.start.value_or(0);
  switch (request.function) {
    case fc::kReportServerId:
      return frame_event(server_id_reply(request, kServerId, kName));
    case fc::kGslReadHolding:
      return frame_event(register_reply(request, read(start, request.count.value_or(0))));
    case fc::kReadWriteMultiple:
      // The write happens before the read (Modbus Application Protocol, 6.17).
      write(request.write_start.value_or(0), request.words);
      return frame_event(register_reply(request, read(start, request.count.value_or(0))));
    case fc::kGslWriteMultiple:
      write(start, request.words);
      return frame_event(write_multiple_reply(request));
    case fc::kWriteSingleCoil:
      coil_ = request.words[0] == 0xFF00;
      return frame_event(echo_of(request));
    default:  // 0x06
      write(start, request.words);
      return frame_event(echo_of(request));
  }
}

}  // namespace pvtap::sim
