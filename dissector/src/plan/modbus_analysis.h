// Works out the ModbusPlan of a frame of the Modbus family: coils, diagnostics, device
// identification, server ID, masks, FIFO and file records, with the core's readers.
#pragma once

#include "plan/arena.h"
#include "plan/frame_plan.h"
#include "pvtap/codec/frame.h"

namespace pvtap::dissector {

// The layout as the tree shows it: the core's, without the fields the Modbus items show
// under names of their own (0x18's FIFO count); call before the register values are placed.
void correct_modbus_layout(const Frame& f, FrameLayout& layout);

// Fills plan.modbus; `request` places a read reply's bits, `with_items` adds the bits and
// objects one by one (the tree is built).
void plan_modbus(const Frame& f, const Frame* request, bool with_items, const Arena& arena,
                 FramePlan& plan);

}  // namespace pvtap::dissector
