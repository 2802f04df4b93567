// Works out the ModbusPlan of a frame of the Modbus family: coils, diagnostics, device
// identification, server ID, masks, FIFO and file records, with the core's readers.
#pragma once

#include "plan/arena.h"
#include "plan/frame_plan.h"
#include "pvtap/codec/frame.h"

namespace pvtap::dissector {

// The places of the fields the core's frame layout leaves out or puts elsewhere for the plain
// Modbus functions (0x08's sub-function, 0x17's write part, 0x18's two-byte byte count);
// call before the register values are placed.
void correct_modbus_layout(const Frame& f, FrameLayout& layout);

// Fills plan.modbus; `request` places a read reply's bits, `with_items` adds the bits and
// objects one by one (the tree is built).
void plan_modbus(const Frame& f, const Frame* request, bool with_items, const Arena& arena,
                 FramePlan& plan);

}  // namespace pvtap::dissector
