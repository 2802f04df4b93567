// CaptureOrder: several capture files put in the order of their records' times, whatever
// order the command line gave them, with the files that cannot be read and the repeats named
// before any output is written.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "pvtap/framing/bus_chunk.h"

namespace pvtap::analyzer {

// PlannedCapture: one capture file as its first record shows it.
struct PlannedCapture {
  std::string path;
  int link_type = -1;
  std::optional<double> first_time;        // nullopt: the file holds no whole record
  std::vector<std::uint8_t> first_record;  // its bytes, to recognise a repeated file
  std::string error;                       // why it cannot be read at all
  // Who sent its bytes: one pair of a 4-wire bus (--duplex), or Unknown (a 2-wire tap).
  Direction direction = Direction::Unknown;
};

// CapturePlan: the files to read, each once, in time order.
struct CapturePlan {
  // By the time of their first record (files without a record last, as given); ring files
  // named cap, cap1 ... cap10 come in the order they were written.
  std::vector<PlannedCapture> readable;
  // Missing, unreadable, not a capture, or of a link type pvtap does not read: in the order
  // given, each with its reason. The other files are read all the same.
  std::vector<PlannedCapture> unreadable;
  // Two files that begin with the same record (the same file twice, or copies): both named.
  std::optional<std::string> refusal;
};

// `duplex`: the first path holds the requests' pair of a 4-wire bus, the second the replies'.
CapturePlan plan_captures(const std::vector<std::string>& paths, bool duplex = false);

// The one-line refusal for two files that hold the same record at `time`.
std::string repeated_records_text(const std::string& a, const std::string& b, double time);

}  // namespace pvtap::analyzer
