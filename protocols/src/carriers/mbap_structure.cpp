#include "pvtap/carriers/mbap_structure.h"

#include "pvtap/carriers/mbap_reader.h"

namespace pvtap {

namespace {
std::uint16_t be16(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint16_t>((b[at] << 8) | b[at + 1]);
}
}  // namespace

std::optional<MbapHeader> read_mbap_header(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < kMbapHeaderBytes) return std::nullopt;
  return MbapHeader{be16(bytes, 0), be16(bytes, 2), be16(bytes, 4), bytes[6]};
}

bool plausible_mbap_header(const MbapHeader& h) {
  return h.protocol_id == 0 && h.length >= kMbapMinLength && h.length <= kMbapMaxLength;
}

bool whole_mbap_adus(std::span<const std::uint8_t> bytes) {
  if (bytes.empty()) return false;
  while (!bytes.empty()) {
    const auto h = read_mbap_header(bytes);
    if (!h || !plausible_mbap_header(*h)) return false;
    const std::size_t size = kMbapCarrierBytes + h->length;
    if (size > bytes.size() || bytes[kMbapHeaderBytes] == 0) return false;
    bytes = bytes.subspan(size);
  }
  return true;
}

}  // namespace pvtap
