// recognize: a whole first frame with every check holding.
#include "pvtap/carriers/solarman_v5_structure.h"

#include "pvtap/carriers/solarman_v5_frame.h"

namespace pvtap::solarman_v5 {

Recognition recognize(std::span<const std::uint8_t> b) {
  if (b.empty()) return Recognition::NeedMore;
  if (b[0] != kStart) return Recognition::No;
  if (b.size() < kHeaderSize) return Recognition::NeedMore;
  const Header h = read_header(b);
  if (h.length > kMaxPayload || !known_control(h.control)) return Recognition::No;
  const std::size_t size = kOverhead + h.length;
  if (b.size() < size) return Recognition::NeedMore;
  const auto frame = b.first(size);
  const bool holds = frame[size - 1] == kEnd && frame[size - kTrailerSize] == checksum_of(frame);
  return holds ? Recognition::Yes : Recognition::No;
}

}  // namespace pvtap::solarman_v5
