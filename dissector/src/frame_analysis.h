// Works out the FramePlan of one frame with the core: parse, match, decode, format.
#pragma once

#include <epan/wmem_scopes.h>

#include <span>

#include "bus_matcher.h"
#include "frame_plan.h"
#include "frame_record.h"
#include "inverter_protocol.h"

namespace pvtap::dissector {

// FrameInput: one frame's bytes and what the stream cut and the transport said about them.
struct FrameInput {
  std::span<const std::uint8_t> bytes;
  Dialect dialect = Dialect::Gsl;
  Role role = Role::Request;
  FrameCheck check;
  bool role_known = false;
};

// AnalysisContext: where the frame is and what to do with it.
struct AnalysisContext {
  const InverterProtocol* protocol = nullptr;
  FrameRecord* record = nullptr;     // this frame's record
  BusMatcher* matcher = nullptr;     // set on the first pass only: feed the frame to it
  wmem_allocator_t* pool = nullptr;  // pinfo->pool, for the plan's texts
  bool with_values = true;           // false: no tree is built, register values are not needed
};

// Fills `plan` (and, on the first pass, the record). Never throws and calls nothing that
// throws: C++ objects used here are gone before the caller builds the tree.
void analyze_frame(const FrameInput& in, const AnalysisContext& ctx, FramePlan& plan) noexcept;

}  // namespace pvtap::dissector
