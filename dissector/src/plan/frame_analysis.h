// Works out the FramePlan of one frame with the core: parse, match, decode, format.
#pragma once

#include <cstdint>
#include <span>

#include "plan/arena.h"
#include "plan/frame_plan.h"
#include "plan/frame_record.h"

namespace pvtap::dissector {

// AnalysisContext: the frame's record, the protocol's settings and where the plan goes.
struct AnalysisContext {
  const RegisterDecoder* decoder = nullptr;  // the effective maps with the preferred options
  const FrameRecord* record = nullptr;       // what the bus session decided about it
  Arena arena;                               // for the plan's texts and values
  const char* check_word = "CRC";            // "CRC" or "checksum", in the summary
  bool verify_check = true;                  // the protocol's preference
  bool with_values = true;  // false: no tree is built, register values are not needed
};

// Fills `plan` from the frame's bytes and its record. Never throws and calls nothing that
// throws: C++ objects used here are gone before the caller builds the tree.
void analyze_frame(std::span<const std::uint8_t> bytes, const AnalysisContext& ctx,
                   FramePlan& plan) noexcept;

}  // namespace pvtap::dissector
