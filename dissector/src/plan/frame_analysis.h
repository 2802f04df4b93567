// Works out the FramePlan of one frame with the core: parse, match, decode, format.
#pragma once

#include <epan/wmem_scopes.h>

#include <span>

#include "plan/frame_plan.h"
#include "plan/frame_record.h"
#include "registration/inverter_protocol.h"

namespace pvtap::dissector {

// AnalysisContext: where the frame is and what to do with it.
struct AnalysisContext {
  const InverterProtocol* protocol = nullptr;  // of the frame's dialect
  const FrameRecord* record = nullptr;         // what the bus session decided about it
  wmem_allocator_t* pool = nullptr;            // pinfo->pool, for the plan's texts
  bool with_values = true;  // false: no tree is built, register values are not needed
};

// Fills `plan` from the frame's bytes and its record. Never throws and calls nothing that
// throws: C++ objects used here are gone before the caller builds the tree.
void analyze_frame(std::span<const std::uint8_t> bytes, const AnalysisContext& ctx,
                   FramePlan& plan) noexcept;

}  // namespace pvtap::dissector
