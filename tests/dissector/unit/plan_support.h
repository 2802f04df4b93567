// Test helper: an Arena over the heap, frames' bytes and plans, and descriptions as text.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "plan/arena.h"
#include "plan/frame_analysis.h"
#include "plan/heap_arena.h"
#include "pvtap/codec/frame_codec.h"
#include "tree/tree_description.h"

namespace pvtap::dissector::test {

// The bytes of a frame the core encodes (with its check).
inline std::vector<std::uint8_t> wire(const Frame& frame) {
  return encode_frame(frame);
}

// The record of a frame the bus session matched, as the plugin's first pass fills it.
inline FrameRecord record_of(Dialect d, Role r, std::uint32_t packet) {
  FrameRecord record;
  record.packet = packet;
  record.dialect = d;
  record.role = r;
  record.matched = true;
  record.values_trusted = true;
  return record;
}

// A request's record that keeps its bytes, to place its reply's words.
inline FrameRecord request_record(const std::vector<std::uint8_t>& bytes, Dialect d,
                                  std::uint32_t packet) {
  FrameRecord record = record_of(d, Role::Request, packet);
  record.bytes = bytes.data();
  record.length = static_cast<std::uint16_t>(bytes.size());
  return record;
}

// Planner: analyze_frame with the built-in maps, into a heap arena.
struct Planner {
  RegisterDecoder decoder;
  HeapArena heap;
  const char* check_word = "CRC";
  bool verify_check = true;
  bool with_values = true;
  std::uint32_t reply_timeout_ms = 0;  // the protocol's preference; 0: not known

  FramePlan plan(const std::vector<std::uint8_t>& bytes, const FrameRecord& record) {
    AnalysisContext ctx;
    ctx.decoder = &decoder;
    ctx.record = &record;
    ctx.arena = heap.arena();
    ctx.check_word = check_word;
    ctx.verify_check = verify_check;
    ctx.with_values = with_values;
    FramePlan out;
    analyze_frame(bytes, ctx, out);
    return out;
  }

  DescriptionContext description(std::size_t length, bool visited = true) {
    return {heap.arena(), static_cast<std::int32_t>(length), visited, check_word, reply_timeout_ms};
  }
};

// One line per item, so that a test compares the whole tree at a glance:
//   "1 Start [2+2] = 1050 \"0x041A (ID 1050)\""     a field (depth, place, value, label)
//   "1 CheckStatus = 1 (generated)"                  a value worked out, with no place
//   "  ! BadCheck on #9: Bad CRC 0x1234, ..."        an expert info on item 9
//   "1 ! Unanswered [0+0]: Request never ..."        an expert info with its own item
std::vector<std::string> lines_of(const TreeDescription& description);

const char* name_of(TreeField field);
const char* name_of(TreeExpert expert);

}  // namespace pvtap::dissector::test
