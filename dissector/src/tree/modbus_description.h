// The items of the plain Modbus functions and of what the bus learned of a Modbus station.
#pragma once

#include "plan/frame_plan.h"
#include "plan/frame_record.h"
#include "tree/tree_builder.h"

namespace pvtap::dissector {

// The station's name, after the station item, when the station named itself before.
void add_station_name(Builder& b, const FramePlan& plan);

// Coils, diagnostics, device identification, server ID, masks, FIFO, file records.
void add_modbus_fields(Builder& b, const FramePlan& plan);

// A request's quantity out of range, and a change of the station's dialect (RTU frames only:
// invrtu's own items).
void add_station_findings(Builder& b, const FramePlan& plan, const FrameRecord& record);

}  // namespace pvtap::dissector
