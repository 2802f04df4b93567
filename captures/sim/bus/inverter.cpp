#include "bus/inverter.h"

#include "bus/frame_shapes.h"
#include "dialects/inverter_dialect.h"

namespace pvtap::sim {
namespace {

DeviceNumber device_of(const RegisterImage& image) {
  const WordList w = image.block(0x1060, 2);
  return {static_cast<std::uint8_t>(w[0] >> 8),
          static_cast<std::uint32_t>((w[0] & 0xFF) << 16 | w[1])};
}

}  // namespace

Inverter::Inverter(std::uint8_t station, Dialect dialect, std::uint64_t seed, Micros start)
    : station_(station), dialect_(dialect), plant_(station, seed, start), image_(dialect) {}

BusEvent Inverter::reply(const PollBlock& block, std::optional<FaultKind> fault, Micros request_end,
                         SimRandom& random) {
  plant_.advance(request_end);
  inverter_dialect(dialect_)->fill_registers(plant_, image_);
  PollBlock sent = block;
  if (fault == FaultKind::CountMismatch) sent.count = static_cast<std::uint16_t>(block.count - 1);
  Frame reply = fault == FaultKind::ErrorReply
                    ? error_reply(dialect_, station_, block, device_of(image_),
                                  random.percent(50) ? 0x02 : 0x06)
                    : read_reply(dialect_, station_, block, image_.block(sent.start, sent.count),
                                 device_of(image_));
  BusEvent rep = frame_event(reply);
  // The first copy of a duplicated reply is an ordinary reply; the second is the fault.
  if (fault && fault != FaultKind::Duplicate) rep.fault = std::string(to_string(*fault));
  if (fault != FaultKind::ErrorReply) rep.values = image_.truth(sent.start, sent.count);
  return rep;
}

}  // namespace pvtap::sim
