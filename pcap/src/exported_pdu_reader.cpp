#include "pvtap/pcap/exported_pdu_reader.h"

#include <bit>

#include "pvtap/pcap/exported_pdu_tags.h"

namespace pvtap {
namespace {

std::uint16_t be16(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint16_t>((b[at] << 8) | b[at + 1]);
}

std::uint32_t be32(std::span<const std::uint8_t> b, std::size_t at) {
  return (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) |
         (std::uint32_t{b[at + 2]} << 8) | std::uint32_t{b[at + 3]};
}

double be_double(std::span<const std::uint8_t> b, std::size_t at) {
  const std::uint64_t bits = (std::uint64_t{be32(b, at)} << 32) | be32(b, at + 4);
  return std::bit_cast<double>(bits);
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
      out.direction = direction_of(static_cast<std::int32_t>(be32(value, 0)));
    } else if (tag == exported_pdu::kTagPvtapRecord) {
      out.pvtap_record = value;
    } else if (tag == exported_pdu::kTagPvtapRun) {
      out.pvtap_run = value;
    }
  }
  out.pdu = record.subspan(at);
  return out;
}

std::optional<RecordFacts> record_facts(std::span<const std::uint8_t> v) {
  const bool counted_loss = v.size() == exported_pdu::kPvtapLossRecordLength;
  if ((v.size() != exported_pdu::kPvtapRecordLength && !counted_loss) ||
      v[0] != exported_pdu::kPvtapTagVersion) {
    return std::nullopt;
  }
  RecordFacts f;
  if (v[1] < static_cast<std::uint8_t>(RecordKind::Frame) ||
      v[1] > static_cast<std::uint8_t>(RecordKind::Loss)) {
    return std::nullopt;
  }
  f.kind = static_cast<RecordKind>(v[1]);
  if (v[2] >= kDirections) return std::nullopt;
  f.stream = static_cast<Direction>(v[2]);
  f.start_time = be_double(v, 4);
  f.end_time = be_double(v, 12);
  if (counted_loss) {
    if (f.kind != RecordKind::Loss) return std::nullopt;
    f.lost_bytes = (std::uint64_t{be32(v, 20)} << 32) | be32(v, 24);
  }
  return f;
}

std::optional<RunFacts> run_facts(std::span<const std::uint8_t> v) {
  if (v.size() < exported_pdu::kPvtapRunFixedLength || v[0] != exported_pdu::kPvtapTagVersion) {
    return std::nullopt;
  }
  RunFacts r;
  r.dialects = dialects_of_bits(v[1]);
  r.baud = be32(v, 4);
  r.timeout = be_double(v, 8);
  const auto name = v.subspan(exported_pdu::kPvtapRunFixedLength);
  r.bus = std::string_view(reinterpret_cast<const char*>(name.data()), name.size());
  return r;
}

std::uint8_t dialect_bits(DialectSet dialects) {
  std::uint8_t bits = dialects.prefers_modbus() ? 0x80 : 0;
  for (const Dialect d : kAllDialects) {
    if (dialects.contains(d)) bits |= static_cast<std::uint8_t>(1u << static_cast<unsigned>(d));
  }
  return bits;
}

DialectSet dialects_of_bits(std::uint8_t bits) {
  DialectSet set = DialectSet::none();
  for (const Dialect d : kAllDialects) {
    if ((bits & (1u << static_cast<unsigned>(d))) != 0) set = set.with(d);
  }
  if (set == DialectSet::none()) return DialectSet::all();
  return (bits & 0x80) != 0 ? set.preferring_modbus() : set;
}

}  // namespace pvtap
