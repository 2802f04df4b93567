// Fuzz target dissector_plan: the plugin's per-frame plan and tree description (what it works
// out before any Wireshark call) on any bytes, with any record the first pass could have left
// (dialect, role, check, pairing, and the request whose bytes place a reply's words). Asserts
// that every item the tree would add, every planned value and every field of the layout lies
// within the frame's bytes, and that experts point at items that exist: in Wireshark an
// item beyond the bytes throws, and this runs on untrusted captures.
#include <cstddef>
#include <cstdint>
#include <optional>

#include "fuzz_input.h"
#include "plan/frame_analysis.h"
#include "plan/heap_arena.h"
#include "pvtap/codec/unknown_function_frame.h"
#include "tree/tree_description.h"

namespace {

using pvtap::dissector::FramePlan;
using pvtap::dissector::FrameRecord;
using pvtap::dissector::TreeDescription;

bool bit(std::uint8_t flags, int n) {
  return ((flags >> n) & 1) != 0;
}

FrameRecord record_from(pvtap::fuzz::FuzzInput& in) {
  FrameRecord r;
  r.dialect = static_cast<pvtap::Dialect>(in.byte() % 3);
  const std::uint8_t flags = in.byte();
  r.role = bit(flags, 0) ? pvtap::Role::Response : pvtap::Role::Request;
  r.matched = bit(flags, 1);
  r.check_ok = bit(flags, 2);
  r.values_trusted = bit(flags, 3);
  r.timed_out = bit(flags, 4);
  r.unsolicited = bit(flags, 5);
  r.duplicate = bit(flags, 6);
  r.has_latency = bit(flags, 7);
  const std::uint8_t more = in.byte();
  r.role_corrected = bit(more, 0);
  r.count_mismatch = bit(more, 1);
  r.count_expected = in.byte();
  r.count_found = in.byte();
  r.latency = static_cast<double>(in.u32() % 5000000) / 1e3;
  r.packet = in.u32();
  r.announced_in = bit(more, 2) ? r.packet + 1 : 0;  // no input of its own: the corpus stays
  return r;
}

void check_span(std::uint16_t offset, std::uint16_t length, std::size_t size) {
  PVTAP_FUZZ_CHECK(static_cast<std::size_t>(offset) + length <= size || length == 0);
}

void check_layout(const pvtap::FrameLayout& l, std::size_t size) {
  for (const pvtap::FieldSpan& s :
       {l.start_delimiter, l.station, l.function, l.byte_count, l.device_type, l.device_serial,
        l.start, l.count, l.exception_code, l.words, l.check, l.end_delimiter}) {
    check_span(s.offset, s.length, size);
  }
}

void check_items(const TreeDescription& d, std::size_t size) {
  for (std::size_t i = 0; i < d.count; ++i) {
    const pvtap::dissector::TreeItem& item = d.items[i];
    PVTAP_FUZZ_CHECK(item.offset >= 0 && item.length >= 0);
    PVTAP_FUZZ_CHECK(
        static_cast<std::size_t>(item.offset) + static_cast<std::size_t>(item.length) <= size);
    PVTAP_FUZZ_CHECK(item.target < static_cast<std::int32_t>(d.count));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const pvtap::RegisterDecoder decoder;
  pvtap::fuzz::FuzzInput in(data, size);
  FrameRecord record = record_from(in);
  // The request that places a reply's words: its own bytes, as the first pass kept them.
  FrameRecord request;
  const auto request_bytes = in.take(in.byte() % 64);
  if (!request_bytes.empty()) {
    request.dialect = record.dialect;
    request.bytes = request_bytes.data();
    request.length = static_cast<std::uint16_t>(request_bytes.size());
    record.placed_by = &request;
    record.request = &request;
  }
  const auto bytes = in.rest();

  pvtap::dissector::HeapArena arena;
  pvtap::dissector::AnalysisContext ctx;
  ctx.decoder = &decoder;
  ctx.record = &record;
  ctx.arena = arena.arena();
  ctx.verify_check = (record.packet & 1) != 0;
  FramePlan plan;
  pvtap::dissector::analyze_frame(bytes, ctx, plan);
  check_layout(plan.layout, bytes.size());
  for (std::size_t i = 0; i < plan.value_count; ++i) {
    check_span(plan.values[i].span.offset, plan.values[i].span.length, bytes.size());
  }

  pvtap::dissector::DescriptionContext dctx;
  dctx.arena = arena.arena();
  dctx.length = static_cast<std::int32_t>(bytes.size());
  dctx.visited = (record.packet & 2) != 0;
  check_items(pvtap::dissector::describe_frame(plan, record, dctx), bytes.size());
  check_items(pvtap::dissector::describe_noise(pvtap::unknown_function_frame(bytes), dctx),
              bytes.size());
  // A timeout announcement has no bytes of its own: every item is generated.
  dctx.length = 0;
  check_items(pvtap::dissector::describe_timeout(record, dctx), 0);
  return 0;
}
