#include "bus/frame_shapes.h"

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
  const auto data_bytes = static_cast<std::uint8_t>(2 * words.size());
  switch (d) {
    case Dialect::Ascii:
      f.start = block.start;
      break;
    case Dialect::Hybrid:
      // Every Hybrid reply starts with the 4-byte device number.
      f.byte_count = static_cast<std::uint8_t>(4 + data_bytes);
      f.device = device;
      break;
    case Dialect::Gsl:
    case Dialect::Modbus:
      f.byte_count = data_bytes;
      break;
  }
  return f;
}

Frame error_reply(Dialect d, std::uint8_t station, const PollBlock& block, DeviceNumber device,
                  std::uint8_t gsl_code) {
  if (d == Dialect::Hybrid) {
    Frame f = make_frame(d, Role::Response, station, fc::kHybridError);
    f.byte_count = 8;
    f.device = device;
    f.start = 0x1000;
    f.count = 0x00FF;
    return f;
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
