#include "pvtap/pcap/exported_pdu_writer.h"

#include <pcap/pcap.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <string_view>

#include "pvtap/framing/framing_probe.h"
#include "pvtap/pcap/exported_pdu_tags.h"
#include "pvtap/pcap/link_types.h"

namespace pvtap {
namespace {

static_assert(dlt::kUpperPdu == DLT_WIRESHARK_UPPER_PDU);

std::size_t put16(std::uint8_t* out, std::uint16_t v) {
  out[0] = static_cast<std::uint8_t>(v >> 8);
  out[1] = static_cast<std::uint8_t>(v);
  return 2;
}

std::size_t put_tag(std::uint8_t* out, std::uint16_t tag, std::uint16_t length) {
  put16(out, tag);
  put16(out + 2, length);
  return 4;
}

std::size_t put32(std::uint8_t* out, std::uint32_t v) {
  put16(out, static_cast<std::uint16_t>(v >> 16));
  put16(out + 2, static_cast<std::uint16_t>(v));
  return 4;
}

std::size_t put_double(std::uint8_t* out, double v) {
  const auto bits = std::bit_cast<std::uint64_t>(v);
  put32(out, static_cast<std::uint32_t>(bits >> 32));
  put32(out + 4, static_cast<std::uint32_t>(bits));
  return 8;
}

// pvtap's record tag: kind, stream, exact first- and last-byte times (exported_pdu_tags.h).
std::size_t put_record_facts(std::uint8_t* out, const RecordFacts& f) {
  const std::uint16_t length =
      f.lost_bytes ? exported_pdu::kPvtapLossRecordLength : exported_pdu::kPvtapRecordLength;
  std::size_t at = put_tag(out, exported_pdu::kTagPvtapRecord, length);
  out[at++] = exported_pdu::kPvtapTagVersion;
  out[at++] = static_cast<std::uint8_t>(f.kind);
  out[at++] = static_cast<std::uint8_t>(f.stream);
  out[at++] = 0;
  at += put_double(out + at, f.start_time);
  at += put_double(out + at, f.end_time);
  if (f.lost_bytes) {
    at += put32(out + at, static_cast<std::uint32_t>(*f.lost_bytes >> 32));
    at += put32(out + at, static_cast<std::uint32_t>(*f.lost_bytes));
  }
  return at;
}

// pvtap's run tag: dialects, baud, timeout and the bus's name.
std::size_t put_run_facts(std::uint8_t* out, const RunFacts& r) {
  const std::size_t name = std::min(r.bus.size(), ExportedPduWriter::kMaxBusName);
  const auto length = static_cast<std::uint16_t>(exported_pdu::kPvtapRunFixedLength + name);
  std::size_t at = put_tag(out, exported_pdu::kTagPvtapRun, length);
  out[at++] = exported_pdu::kPvtapTagVersion;
  out[at++] = dialect_bits(r.dialects);
  out[at++] = 0;
  out[at++] = 0;
  at += put32(out + at, r.baud);
  at += put_double(out + at, r.timeout);
  std::copy_n(r.bus.begin(), name, out + at);
  return at + name;
}

// Dissector name tag (padded with NULs to a multiple of 4, as Wireshark writes it), direction
// tag (when known), pvtap's tags (when given), end tag.
std::size_t put_tags(std::uint8_t* out, std::string_view name, Direction direction,
                     const RecordFacts* facts, const RunFacts* run) {
  std::size_t at = 0;
  const auto padded = static_cast<std::uint16_t>((name.size() + 3) / 4 * 4);
  at += put_tag(out + at, exported_pdu::kTagDissectorName, padded);
  std::fill_n(out + at, padded, std::uint8_t{0});
  std::copy(name.begin(), name.end(), out + at);
  at += padded;
  if (direction != Direction::Unknown) {
    at += put_tag(out + at, exported_pdu::kTagP2pDirection, 4);
    const std::int32_t p2p = direction == Direction::ToSlave ? exported_pdu::kDirectionSent
                                                             : exported_pdu::kDirectionReceived;
    at += put32(out + at, static_cast<std::uint32_t>(p2p));
  }
  if (facts != nullptr) at += put_record_facts(out + at, *facts);
  if (run != nullptr) at += put_run_facts(out + at, *run);
  at += put_tag(out + at, exported_pdu::kTagEnd, 0);
  return at;
}

}  // namespace

bool ExportedPduWriter::open(const std::string& path) {
  return file_.open(path, DLT_WIRESHARK_UPPER_PDU);
}

void ExportedPduWriter::write_frame(double time, Role role, std::span<const std::uint8_t> frame) {
  write(time, role == Role::Request ? Direction::ToSlave : Direction::FromSlave, frame);
}

void ExportedPduWriter::write_noise(double time, Direction direction,
                                    std::span<const std::uint8_t> noise) {
  // The reassembler reports long noise in runs of at most 4 KiB; longer ones are split.
  constexpr std::size_t kMaxRun = 4096;
  for (std::size_t at = 0; at < noise.size(); at += kMaxRun) {
    write(time, direction, noise.subspan(at, std::min(kMaxRun, noise.size() - at)));
  }
}

void ExportedPduWriter::write_record(const RecordFacts& facts, const RunFacts* run,
                                     Direction direction, std::span<const std::uint8_t> bytes) {
  write(facts.end_time, direction, bytes, &facts, run);
}

void ExportedPduWriter::write_end(double time) {
  const RecordFacts facts{RecordKind::End, Direction::Unknown, time, time, {}};
  write_event(facts, nullptr, "end of the run: requests still waiting were judged here");
}

void ExportedPduWriter::write_loss(double time, Direction stream,
                                   std::optional<std::uint64_t> lost_bytes, const RunFacts* run) {
  const RecordFacts facts{RecordKind::Loss, stream, time, time, lost_bytes};
  const char* side = stream == Direction::ToSlave     ? " of the master's side"
                     : stream == Direction::FromSlave ? " of the slaves' side"
                                                      : "";
  const std::string text = "capture data lost" + std::string(side) + ": " +
                           (lost_bytes ? std::to_string(*lost_bytes) + " bytes" : "bytes unknown");
  write_event(facts, run, text);
}

void ExportedPduWriter::write_event(const RecordFacts& facts, const RunFacts* run,
                                    std::string_view text) {
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(text.data());
  write(facts.end_time, Direction::Unknown, {bytes, text.size()}, &facts, run,
        exported_pdu::kEventDissectorName);
}

void ExportedPduWriter::write(double time, Direction direction, std::span<const std::uint8_t> bytes,
                              const RecordFacts* facts, const RunFacts* run,
                              std::string_view dissector) {
  if (!file_.is_open()) return;
  constexpr std::size_t kMaxTags = 128 + kMaxBusName;
  static_assert(sizeof(record_) >= kMaxTags + 4096 &&
                sizeof(record_) >= kMaxTags + kMaxFrameLength);
  const std::size_t tags = put_tags(record_.data(), dissector, direction, facts, run);
  const std::size_t length = std::min(bytes.size(), record_.size() - tags);
  std::copy_n(bytes.begin(), length, record_.begin() + static_cast<std::ptrdiff_t>(tags));
  // A capture timestamp may be any 64-bit value: held to what int64 microseconds can count.
  constexpr double kMaxSeconds = 9.2e12;  // 9.2e18 us, just under 2^63
  const double held = std::isnan(time) ? 0 : std::clamp(time, -kMaxSeconds, kMaxSeconds);
  const double seconds = std::floor(held);
  const std::int64_t micros =
      static_cast<std::int64_t>(seconds) * 1'000'000 + std::lround((held - seconds) * 1e6);
  file_.write(micros, std::span(record_).first(tags + length));
  if (flush_each_record_) file_.flush();
  ++records_;
}

bool ExportedPduWriter::close() {
  return file_.close();
}

}  // namespace pvtap
