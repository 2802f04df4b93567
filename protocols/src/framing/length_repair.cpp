#include "framing/length_repair.h"

#include <array>
#include <cstdint>

#include "dialects/dialect_module.h"
#include "pvtap/codec/checksums.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {
namespace {

constexpr std::array<std::uint8_t, 15> kRtuFunctions{
    fc::kGslReadHolding,
    fc::kGslReadInput,
    fc::kGslWriteSingle,
    fc::kGslWriteMultiple,
    fc::kGslReadHolding | fc::kExceptionFlag,
    fc::kGslReadInput | fc::kExceptionFlag,
    fc::kGslWriteSingle | fc::kExceptionFlag,
    fc::kGslWriteMultiple | fc::kExceptionFlag,
    fc::kHybridDeviceInfo,
    fc::kHybridRunningData,
    fc::kHybridSettings,
    fc::kHybridManufacturer,
    fc::kHybridWriteParameter,
    fc::kHybridRestoreFactory,
    fc::kHybridError,
};

using Buffer = std::array<std::uint8_t, kMaxRtuFrameLength>;

bool crc_matches(std::span<const std::uint8_t> frame) {
  const std::size_t body = frame.size() - 2;
  const auto found = static_cast<std::uint16_t>(frame[body] | (frame[body + 1] << 8));
  return Crc16Modbus::compute(frame.first(body)) == found;
}

// The RTU reading of `bytes` that spans all of them, if the length rules allow one.
std::optional<FrameCandidate> spanning_reading(std::span<const std::uint8_t> bytes, RoleHint hint,
                                               DialectSet dialects) {
  const CandidateList cands = frame_candidates(bytes, hint, dialects, Plausibility::Ignore);
  for (std::size_t i = 0; i < cands.size; ++i) {
    const FrameCandidate& c = cands.items[i];
    if (detail::dialect_module(c.dialect).rtu_framed && c.length == bytes.size()) return c;
  }
  return std::nullopt;
}

// Tries one value for the byte at `at`: the reading it gives, if that spans the frame and
// makes the CRC match.
std::optional<FrameCandidate> try_value(Buffer& buf, std::span<const std::uint8_t> frame,
                                        std::size_t at, std::uint8_t value, RoleHint hint,
                                        DialectSet dialects) {
  if (at >= frame.size() || frame[at] == value) return std::nullopt;
  const std::span<const std::uint8_t> trial(buf.data(), frame.size());
  buf[at] = value;
  // The length rules are cheap and rule most values out; the CRC is checked only for those
  // that give the span's length.
  std::optional<FrameCandidate> found = spanning_reading(trial, hint, dialects);
  if (found && !crc_matches(trial)) found.reset();
  buf[at] = frame[at];
  return found;
}

// Where a byte count sits for the function of the frame, and the value the span implies.
struct CountField {
  std::size_t at;
  std::size_t overhead;
};

CountField count_field(std::uint8_t function) {
  // Replies of reads (both dialects) and every Hybrid reply count their data at byte 2; a
  // GSL write of several registers counts its data at byte 6.
  return function == fc::kGslWriteMultiple ? CountField{6, 9} : CountField{2, 5};
}

// A write of several registers or coils: its request counts its data after its quantities.
bool counted_write(std::uint8_t function) {
  return function == fc::kGslWriteMultiple || function == fc::kWriteMultipleCoils ||
         function == fc::kReadWriteMultiple;
}

}  // namespace

std::optional<FrameCandidate> lying_count_reading(std::span<const std::uint8_t> frame,
                                                  RoleHint hint, DialectSet dialects) {
  if (!dialects.rtu() || frame.size() < kMinRtuFrameLength || frame.size() > kMaxRtuFrameLength ||
      !counted_write(frame[1]) || !crc_matches(frame)) {
    return std::nullopt;
  }
  const CandidateList cands = frame_candidates(frame, hint, dialects, Plausibility::Ignore);
  for (std::size_t i = 0; i < cands.size; ++i) {
    const FrameCandidate& c = cands.items[i];
    if (!detail::dialect_module(c.dialect).rtu_framed || c.role != Role::Request ||
        c.length == frame.size()) {
      continue;
    }
    return FrameCandidate{frame.size(), c.dialect, c.role, true};
  }
  return std::nullopt;
}

std::optional<FrameCandidate> repaired_reading(std::span<const std::uint8_t> frame, RoleHint hint,
                                               DialectSet dialects) {
  if (!dialects.rtu() || frame.size() < kMinRtuFrameLength || frame.size() > kMaxRtuFrameLength) {
    return std::nullopt;
  }
  Buffer buf{};
  std::copy(frame.begin(), frame.end(), buf.begin());
  for (const std::uint8_t f : kRtuFunctions) {
    if (auto c = try_value(buf, frame, 1, f, hint, dialects)) return c;
  }
  const CountField field = count_field(frame[1]);
  if (frame.size() < field.overhead || frame.size() - field.overhead > 0xFF) return std::nullopt;
  const auto n = static_cast<std::uint8_t>(frame.size() - field.overhead);
  return try_value(buf, frame, field.at, n, hint, dialects);
}

}  // namespace pvtap::detail
