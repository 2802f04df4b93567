// FaultPlan: how often each kind of fault is injected, parsed from "kind=percent,...".
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace pvtap::sim {

enum class FaultKind : unsigned {
  Corrupt,         // one bit or byte of a reply changed, any byte: bad check (or ASCII noise)
  Missing,         // no reply: the master times out
  Slow,            // a reply that comes late, still inside the timeout
  Noise,           // a burst of bytes of no frame after a reply
  ErrorReply,      // GSL exception / Hybrid 0xFF error reply (ASCII: no reply, its error path)
  CountMismatch,   // a reply with fewer registers than asked for
  Duplicate,       // the same reply twice
  CorruptRequest,  // one bit or byte of a request changed, any byte: the slave stays silent
  CorruptData,     // one data byte of a reply changed, and the next request follows closely
};
inline constexpr std::size_t kFaultKinds = 9;
// Kinds from here on were added after the sample library was written: they are drawn, and
// named in the ground truth, only when a plan asks for them, so every seed keeps its bytes.
inline constexpr unsigned kFirstOptInKind = 8;

std::string_view to_string(FaultKind kind);

struct FaultPlan {
  std::array<unsigned, kFaultKinds> percent{};  // chance per poll
  unsigned& operator[](FaultKind k) { return percent[static_cast<unsigned>(k)]; }
  unsigned operator[](FaultKind k) const { return percent[static_cast<unsigned>(k)]; }
  // Whether a poll draws for this kind at all (see kFirstOptInKind).
  bool drawn(FaultKind k) const {
    return static_cast<unsigned>(k) < kFirstOptInKind || (*this)[k] > 0;
  }
};

// "none", "all" (every kind at 4 %) or "corrupt=5,corrupt_request=3,...". nullopt with `error` set
// when the text names an unknown kind or a bad number.
std::optional<FaultPlan> parse_fault_plan(std::string_view text, std::string& error);

}  // namespace pvtap::sim
