#include "devices/io_module.h"

#include <cmath>

#include "bus/frame_shapes.h"
#include "dialects/modbus_frames.h"
#include "plant/plant_model.h"
#include "pvtap/codec/function_codes.h"
#include "sim_random.h"

namespace pvtap::sim {

IoModule::IoModule(std::uint8_t station, std::uint64_t seed)
    : ModbusDevice(station), seed_(seed ^ 0x10D0ull * (station + 1)) {}

DeviceLabel IoModule::label() const {
  return {"io_module", {}, {}, {}, {}};
}

std::vector<Frame> IoModule::requests(unsigned round) const {
  const std::uint8_t s = station();
  std::vector<Frame> out{modbus_read(s, fc::kReadDiscreteInputs, 0, kPoints),
                         modbus_read(s, fc::kReadCoils, 0, kPoints),
                         modbus_read(s, fc::kGslReadInput, 0, 2)};
  // Coil 0..7 switched one at a time, on for eight rounds and off for eight; coils 8..15 set
  // together to the round's number every other round.
  if (round % 2 == 0) {
    out.push_back(
        write_single_coil(s, static_cast<std::uint16_t>(round / 2 % 8), round / 16 % 2 == 0));
  } else {
    std::vector<bool> states(8);
    for (unsigned i = 0; i < 8; ++i) states[i] = (round >> i & 1u) != 0;
    out.push_back(write_multiple_coils(s, 8, states));
  }
  // The export limit setpoint: read, written alone, written with its ramp time.
  const auto limit = static_cast<std::uint16_t>(100 - round % 40);
  if (round % 3 == 0) {
    out.push_back(modbus_read(s, fc::kGslReadHolding, kSetpoint, 2));
  } else if (round % 3 == 1) {
    out.push_back(write_single_register(s, kSetpoint, limit));
  } else {
    out.push_back(write_multiple_registers(
        s, kSetpoint, WordList{limit, static_cast<std::uint16_t>(30 + round % 30)}));
  }
  return out;
}

// Input i is a contact that changes state every 10 + 7·i seconds, at random.
std::vector<bool> IoModule::inputs_at(Micros now) const {
  std::vector<bool> states(kPoints);
  for (std::uint16_t i = 0; i < kPoints; ++i) {
    const auto window = static_cast<std::uint64_t>(now / ((10 + 7 * i) * 1'000'000ll));
    SimRandom r(seed_ ^ (window * 0x9E37ull + i));
    states[i] = r.percent(50);
  }
  return states;
}

std::vector<bool> IoModule::bits(const std::vector<bool>& all, const Frame& request) const {
  std::vector<bool> out;
  const unsigned start = request.start.value_or(0), count = request.count.value_or(0);
  for (unsigned i = start; i < start + count; ++i) out.push_back(i < all.size() && all[i]);
  return out;
}

// Analog inputs 0 and 1: 4-20 mA loops in tenths of a mA (irradiance and module temperature
// sensors), which follow the sun. Holding registers: the setpoints.
WordList IoModule::words(const Frame& request, Micros now) const {
  const double sun = daylight(now);
  WordList out;
  const unsigned start = request.start.value_or(0), count = request.count.value_or(0);
  for (unsigned a = start; a < start + count; ++a) {
    if (request.function == fc::kGslReadInput)
      out.push_back(static_cast<std::uint16_t>(std::lround(40 + 160 * (a == 0 ? sun : 0.6 * sun))));
    else
      out.push_back(a >= kSetpoint && a < kSetpoint + 2 ? setpoint_[a - kSetpoint] : 0);
  }
  return out;
}

void IoModule::apply_write(const Frame& request) {
  const unsigned start = request.start.value_or(0);
  switch (request.function) {
    case fc::kWriteSingleCoil:
      if (start < kPoints) coils_[start] = request.words[0] == 0xFF00;
      break;
    case fc::kWriteMultipleCoils:
      for (unsigned i = 0; i < request.count.value_or(0) && start + i < kPoints; ++i)
        coils_[start + i] = ((unsigned{request.data[i / 8]} >> (i % 8)) & 1u) != 0;
      break;
    default:  // 0x06 and 0x10: the setpoints
      for (unsigned i = 0; i < request.words.size(); ++i)
        if (start + i >= kSetpoint && start + i < kSetpoint + 2)
          setpoint_[start + i - kSetpoint] = request.words[i];
      break;
  }
}

BusEvent IoModule::reply(const Frame& request, Micros request_end) {
  switch (request.function) {
    case fc::kReadCoils:
      return frame_event(bits_reply(request, bits(coils_, request)));
    case fc::kReadDiscreteInputs:
      return frame_event(bits_reply(request, bits(inputs_at(request_end), request)));
    case fc::kGslReadHolding:
    case fc::kGslReadInput:
      return frame_event(register_reply(request, words(request, request_end)));
    case fc::kGslWriteMultiple:
    case fc::kWriteMultipleCoils:
      apply_write(request);
      return frame_event(write_multiple_reply(request));
    default:  // 0x05 0x06 0x08: the echo
      if (request.function != fc::kDiagnostics) apply_write(request);
      return frame_event(echo_of(request));
  }
}

}  // namespace pvtap::sim
