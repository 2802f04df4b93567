#include "bus/frame_shapes.h"

#include "dialects/inverter_dialect.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::sim {

Frame read_request(Dialect d, std::uint8_t station, const PollBlock& block) {
  Frame f = make_frame(d, Role::Request, station, block.function);
  f.start = block.start;
  f.count = block.count;
  return f;
}

Frame read_reply(Dialect d, std::uint8_t station, const PollBlock& block, const WordList& words,
                 DeviceNumber device) {
  Frame f = make_frame(d, Role::Response, station, block.function);
  f.words = words;
  if (const InverterDialect* inverter = inverter_dialect(d)) {
    inverter->shape_read_reply(f, block, device);
  } else {
    f.byte_count = static_cast<std::uint8_t>(2 * words.size());
  }
  return f;
}

Frame error_reply(Dialect d, std::uint8_t station, const PollBlock& block, DeviceNumber device,
                  std::uint8_t gsl_code) {
  const InverterDialect* inverter = inverter_dialect(d);
  if (inverter != nullptr && inverter->error_reply != nullptr) {
    return inverter->error_reply(station, device);
  }
  Frame f = make_frame(d, Role::Response, station,
                       static_cast<std::uint8_t>(block.function | fc::kExceptionFlag));
  f.exception_code = gsl_code;
  return f;
}

BusEvent frame_event(const Frame& frame) {
  BusEvent e;
  e.bytes = encode_frame(frame);
  e.dialect = frame.dialect;
  e.role = frame.role;
  e.station = frame.station;
  e.function = frame.function;
  return e;
}

}  // namespace pvtap::sim
