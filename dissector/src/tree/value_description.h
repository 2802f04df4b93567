// The items of a frame's register values: values, flags, station map entries and their warnings.
#pragma once

#include "plan/frame_plan.h"
#include "tree/tree_builder.h"

namespace pvtap::dissector {

// Each planned value with its flags and warnings, then the note on words without a start.
void add_values(Builder& b, const FramePlan& plan);

}  // namespace pvtap::dissector
