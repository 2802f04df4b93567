// Fuzz target frame_codec: the frame parser, the check verifier, the encoder and the framing
// probe on arbitrary bytes, for every dialect, role and role hint.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fuzz_input.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/codec/frame_layout.h"
#include "pvtap/framing/framing_probe.h"

namespace {

using pvtap::Dialect;
using pvtap::Role;
using pvtap::RoleHint;

constexpr Dialect kDialects[] = {Dialect::Ascii, Dialect::Hybrid, Dialect::Gsl, Dialect::Modbus};
constexpr RoleHint kHints[] = {RoleHint::Unknown, RoleHint::Request, RoleHint::Response};

// A frame that parses lays out inside its bytes and, re-encoded, parses back to itself.
void parse_each_reading(std::span<const std::uint8_t> bytes) {
  for (const Dialect d : kDialects) {
    (void)pvtap::verify_check(bytes, d);
    for (const Role role : {Role::Request, Role::Response}) {
      const auto parsed = pvtap::parse_frame(bytes, d, role);
      if (!parsed) {
        PVTAP_FUZZ_CHECK(!parsed.diagnostics().empty());
        continue;
      }
      const auto layout = pvtap::frame_layout(parsed.value(), bytes.size());
      PVTAP_FUZZ_CHECK(layout.check.offset + layout.check.length <= bytes.size());
      PVTAP_FUZZ_CHECK(layout.words.offset + layout.words.length <= bytes.size());
      const auto wire = pvtap::encode_frame(parsed.value());
      if (wire.empty()) continue;
      const auto again = pvtap::parse_frame(wire, d, role);
      PVTAP_FUZZ_CHECK(again && again.value() == parsed.value());
      PVTAP_FUZZ_CHECK(pvtap::verify_check(wire, d).ok);
    }
  }
}

// The dialect sets of the probe: each one alone, and all of them.
pvtap::DialectSet dialects_of(std::uint8_t selector) {
  auto set = pvtap::DialectSet::none();
  for (const Dialect d : kDialects) {
    if (selector & (1u << static_cast<unsigned>(d))) set = set.with(d);
  }
  return set == pvtap::DialectSet::none() ? pvtap::DialectSet::all() : set;
}

void probe_each_hint(std::span<const std::uint8_t> bytes, pvtap::DialectSet dialects) {
  for (const RoleHint hint : kHints) {
    const auto candidates = pvtap::frame_candidates(bytes, hint, dialects);
    PVTAP_FUZZ_CHECK(candidates.size <= pvtap::CandidateList::kMax);
    for (std::size_t i = 0; i < candidates.size; ++i) {
      PVTAP_FUZZ_CHECK(candidates.items[i].length <= pvtap::kMaxFrameLength);
      PVTAP_FUZZ_CHECK(dialects.contains(candidates.items[i].dialect));
    }
    const auto probe = pvtap::probe_frame(bytes, hint, dialects);
    if (probe.status == pvtap::ProbeResult::Status::Complete) {
      PVTAP_FUZZ_CHECK(probe.length > 0 && probe.length <= bytes.size());
      PVTAP_FUZZ_CHECK(dialects.contains(probe.dialect));
      const auto check = pvtap::verify_check(bytes.first(probe.length), probe.dialect);
      PVTAP_FUZZ_CHECK(check.ok == probe.check.ok);
    } else if (probe.status == pvtap::ProbeResult::Status::NeedMore) {
      PVTAP_FUZZ_CHECK(probe.more > 0);
      PVTAP_FUZZ_CHECK(bytes.size() + probe.more <= pvtap::kMaxFrameLength);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pvtap::fuzz::FuzzInput in(data, size);
  const auto dialects = dialects_of(in.byte());
  const auto bytes = in.rest();
  parse_each_reading(bytes);
  probe_each_hint(bytes, dialects);
  return 0;
}
