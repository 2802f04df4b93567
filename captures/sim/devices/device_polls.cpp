// BusMaster's polls of the plain Modbus devices: the same faults as the inverters', where a
// request of that kind can have them.
#include <functional>

#include "bus/bus_master.h"
#include "bus/frame_shapes.h"
#include "devices/battery.h"
#include "devices/energy_meter.h"
#include "devices/io_module.h"
#include "devices/sunspec_inverter.h"
#include "devices/test_suite_server.h"
#include "dialects/modbus_frames.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::sim {
namespace {

bool reads_registers(const Frame& r) {
  return r.function == fc::kGslReadHolding || r.function == fc::kGslReadInput;
}

bool reads_bits(const Frame& r) {
  return r.function == fc::kReadCoils || r.function == fc::kReadDiscreteInputs;
}

// The request a reply one register (bits: one byte) short answers, or nullopt when the
// request is no read that could be short.
std::optional<Frame> shortened(const Frame& request) {
  Frame f = request;
  const std::uint16_t count = request.count.value_or(0);
  if (reads_registers(request) && count > 1)
    f.count = static_cast<std::uint16_t>(count - 1);
  else if (reads_bits(request) && count > 8)
    f.count = static_cast<std::uint16_t>(count - 8);
  else
    return std::nullopt;
  return f;
}

// Faults that need a reply of a certain shape are left out where the request has none: a count
// one short needs a read, damage to the data alone a register read (whose header gives its
// length; a device identification's length is inside its data).
std::optional<FaultKind> fitting(std::optional<FaultKind> fault, const Frame& request,
                                 const ModbusDevice& device) {
  if (fault == FaultKind::CountMismatch && !shortened(request)) return std::nullopt;
  if (fault == FaultKind::CorruptData && !reads_registers(request)) return std::nullopt;
  // An echo sent twice is a third copy of the request's bytes: on a carrier without
  // directions (USB chunks) a master repeating its request reads the same.
  const bool echoed = request.function == fc::kWriteSingleCoil ||
                      request.function == fc::kGslWriteSingle ||
                      request.function == fc::kDiagnostics;
  if (fault == FaultKind::Duplicate && echoed) return std::nullopt;
  if (fault == FaultKind::Corrupt && echoed && device.keeps_echoes_whole()) return std::nullopt;
  return fault;
}

}  // namespace

void BusMaster::add_devices() {
  const std::vector<Inverter>* inverters = &inverters_;
  const auto plant_kw = [inverters] {
    double kw = 0.0;
    for (const Inverter& inv : *inverters)
      if (inv.plant().producing) kw += inv.plant().pv_kw * 0.96;
    return kw;
  };
  if (config_.meter_station)
    devices_.push_back(std::make_unique<EnergyMeter>(
        *config_.meter_station, config_.seed, config_.start, plant_kw, config_.meter_low_first));
  if (config_.battery_station)
    devices_.push_back(
        std::make_unique<Battery>(*config_.battery_station, config_.seed, config_.start));
  if (config_.sunspec_station)
    devices_.push_back(
        std::make_unique<SunSpecInverter>(*config_.sunspec_station, config_.seed, config_.start));
  if (config_.io_module_station)
    devices_.push_back(std::make_unique<IoModule>(*config_.io_module_station, config_.seed));
  if (config_.test_server_station)
    devices_.push_back(std::make_unique<TestSuiteServer>(*config_.test_server_station));
}

BusEvent BusMaster::device_reply(ModbusDevice& device, const Frame& request,
                                 std::optional<FaultKind> fault, Micros request_end) {
  if (fault == FaultKind::ErrorReply) {
    // 0x02 illegal data address, 0x06 server busy.
    BusEvent rep = frame_event(exception_reply(request, random_.percent(50) ? 0x02 : 0x06));
    rep.fault = std::string(to_string(*fault));
    return rep;
  }
  const Frame asked = fault == FaultKind::CountMismatch ? *shortened(request) : request;
  BusEvent rep = device.reply(asked, request_end);
  // The first copy of a duplicated reply is an ordinary reply; the second is the fault.
  if (fault && fault != FaultKind::Duplicate) rep.fault = std::string(to_string(*fault));
  return rep;
}

// A read to a station nobody has: the master waits out its timeout, then a peer puts that
// station's reply on the line (late, for a request already given up).
Micros BusMaster::late_reply_from_absent(ModbusDevice& device, const Frame& request, Micros at) {
  const Micros request_end = wire_.put(frame_event(request), at);
  timeline_.timeouts.push_back({at, request_end, request.station, request.function, {}});
  BusEvent rep = device.reply(request, request_end);
  const Micros reply_at = timeout_after(request_end) + random_.between(20, 60) * 1000;
  rep.latency = reply_at - request_end;
  rep.fault = "late_reply";
  return wire_.put(std::move(rep), reply_at) + random_.between(20, 60) * 1000;
}

// A request the server refuses: a user-defined function (`user_defined_function`, exception
// 0x01), a write whose byte count disagrees with its quantity and its data
// (`write_count_mismatch`) or says fewer bytes than it carries (`byte_count_lies`; its CRC
// covers all it carries), both exception 0x03.
Micros BusMaster::refused_request(const Frame& request, Micros at) {
  BusEvent sent = frame_event(request);
  const bool user_defined = fc::is_user_defined_function(request.function);
  const bool lies = request.byte_count.value_or(0) != 2 * request.words.size();
  sent.fault = user_defined ? "user_defined_function"
               : lies       ? "byte_count_lies"
                            : "write_count_mismatch";
  const Micros request_end = wire_.put(std::move(sent), at);
  BusEvent rep = frame_event(exception_reply(request, user_defined ? 0x01 : 0x03));
  rep.fault = std::string(to_string(FaultKind::ErrorReply));  // counted with the exceptions
  rep.latency = random_.between(15, 60) * 1000;
  const Micros reply_at = request_end + rep.latency;
  return wire_.put(std::move(rep), reply_at) + random_.between(20, 60) * 1000;
}

Micros BusMaster::poll_device(ModbusDevice& device, const Frame& request, Micros at) {
  switch (device.answer_of(request)) {
    case ModbusDevice::Answer::LateFromAbsent:
      return late_reply_from_absent(device, request, at);
    case ModbusDevice::Answer::Broadcast: {
      // Nobody answers (the only broadcast a device asks for is a read, which the specification
      // does not allow): the master waits its turnaround delay, and no timeout.
      BusEvent sent = frame_event(request);
      sent.fault = "broadcast_read";
      return wire_.put(std::move(sent), at) + random_.between(100, 200) * 1000;
    }
    case ModbusDevice::Answer::Refused:
      return refused_request(request, at);
    case ModbusDevice::Answer::Normal:
      break;
  }
  const std::optional<FaultKind> fault =
      placed(fitting(pick_fault(request.dialect), request, device));
  next_request_pins_ = false;
  device.answered(request, !fault);
  if (fault == FaultKind::CorruptRequest) return send_damaged_requests(request, at);
  const Micros request_end = wire_.put(frame_event(request), at);
  if (fault)
    timeline_.faults.push_back({request_end, request.station, std::string(to_string(*fault))});
  const TimeoutTruth asked{at, request_end, request.station, request.function, {}};
  if (fault == FaultKind::Missing) {
    timeline_.timeouts.push_back(asked);
    return timeout_after(request_end);
  }
  return answer(device_reply(device, request, fault, request_end), fault, asked);
}

}  // namespace pvtap::sim
