#include "pvtap/capture/exported_pdu_reader.h"

#include "pvtap/capture/exported_pdu_tags.h"

namespace pvtap {
namespace {

std::uint16_t be16(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint16_t>((b[at] << 8) | b[at + 1]);
}

Direction direction_of(std::int32_t p2p) {
  if (p2p == exported_pdu::kDirectionSent) return Direction::ToSlave;
  if (p2p == exported_pdu::kDirectionReceived) return Direction::FromSlave;
  return Direction::Unknown;
}

}  // namespace

std::optional<ExportedPdu> exported_pdu_record(std::span<const std::uint8_t> record) {
  ExportedPdu out;
  std::size_t at = 0;
  for (;;) {
    if (record.size() < at + 4) return std::nullopt;
    const std::uint16_t tag = be16(record, at);
    const std::uint16_t length = be16(record, at + 2);
    at += 4;
    if (record.size() < at + length) return std::nullopt;
    const auto value = record.subspan(at, length);
    at += length;
    if (tag == exported_pdu::kTagEnd) break;
    if (tag == exported_pdu::kTagDissectorName) {
      std::string_view name(reinterpret_cast<const char*>(value.data()), value.size());
      while (!name.empty() && name.back() == '\0') name.remove_suffix(1);
      out.dissector = name;
    } else if (tag == exported_pdu::kTagP2pDirection && length == 4) {
      const auto raw = (std::uint32_t{value[0]} << 24) | (std::uint32_t{value[1]} << 16) |
                       (std::uint32_t{value[2]} << 8) | std::uint32_t{value[3]};
      out.direction = direction_of(static_cast<std::int32_t>(raw));
    }
  }
  out.pdu = record.subspan(at);
  return out;
}

}  // namespace pvtap
