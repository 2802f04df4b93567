// Renders a bus plan as the serial sniffers would have captured it.
#pragma once

#include <cstddef>
#include <string>

#include "bus_plan.h"
#include "pvtap/pcap/capture_writer.h"

namespace pvtap::forge {

// USER0: the bytes a USB adapter delivered per latency-timer tick (16 ms by default), one
// record per tick, stamped at the tick's end: frames split and merged at random-looking places.
void write_timer_chunks(const BusPlan& plan, CaptureWriter& out, double tick = 0.016);

// RTAC serial (link type 250): up to `chunk` bytes per record behind the 12-byte header,
// stamped with the last byte's end. Items listed in `dropped` are left out and a
// CAPTURE_DATA_LOST record is written in their place.
void write_rtac_records(const BusPlan& plan, CaptureWriter& out, std::size_t chunk,
                        const std::vector<std::size_t>& dropped = {});

// A plain dump of the bus bytes, as `cat /dev/ttyUSB0 > file` makes it.
void write_raw_dump(const BusPlan& plan, const std::string& path);

}  // namespace pvtap::forge
