// Collects the RTU readings at one position for the candidate rules of each dialect (private).
#pragma once

#include <span>

#include "pvtap/framing/framing_probe.h"

namespace pvtap::detail {

// A reading whose length needs a byte not yet seen records that need. `strict` rules out
// readings with implausible fields; the length rules hold either way.
struct CandidateReader {
  std::span<const std::uint8_t> b;
  Dialect dialect;
  bool strict;
  CandidateList& out;

  bool has(std::size_t i) {
    if (i < b.size()) return true;
    const std::size_t need = i + 1 - b.size();
    if (out.need_header == 0 || need < out.need_header) out.need_header = need;
    return false;
  }
  unsigned word(std::size_t at) const { return (unsigned{b[at]} << 8) | b[at + 1]; }
  // Set by reject_implausible for the reading being made; cleared by every add.
  bool implausible = false;

  // Whether to drop a reading whose fields break the specification's ranges: always when
  // hunting; at a pinned position it stays, as a frame only with a good check (a request with
  // an out-of-range quantity is a finding on a frame, not noise).
  bool reject_implausible() {
    if (strict) return true;
    implausible = true;
    return false;
  }
  void add(std::size_t length, Role role) {
    out.add({length, dialect, role, implausible});
    implausible = false;
  }
  void add_unjudged(std::size_t length, Role role) { out.add({length, dialect, role, true}); }
};

// A read reply must fit its data in one byte count.
inline constexpr unsigned kMaxReadCount = 125;

// The readings of the public Modbus codes GSL does not use (dialects/modbus/
// modbus_candidates.cpp; Hybrid's and GSL's are inline in their folders' headers).
void add_modbus_request(CandidateReader& r, std::uint8_t f);
void add_modbus_response(CandidateReader& r, std::uint8_t f);

}  // namespace pvtap::detail
