#include "pvtap/codec/noise_resemblance.h"

#include <algorithm>

#include "dialects/ascii/ascii_codec.h"

namespace pvtap {

bool resembles_ascii_frame(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < 2 || (bytes[0] != detail::kEnq && bytes[0] != detail::kAck)) return false;
  const auto rest = bytes.subspan(1);
  const auto fitting = std::count_if(rest.begin(), rest.end(), [](std::uint8_t b) {
    return (b >= 0x20 && b <= 0x7E) || b == detail::kEot;
  });
  return 4 * static_cast<std::size_t>(fitting) >= 3 * rest.size();
}

}  // namespace pvtap
