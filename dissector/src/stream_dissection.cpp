#include "stream_dissection.h"

#include <epan/proto_data.h>

#include <span>

#include "frame_analysis.h"
#include "frame_tree.h"
#include "pvtap/segment_cut.h"
#include "response_time_stats.h"

namespace pvtap::dissector {
namespace {

// PacketCounters: how many frames and pieces of a protocol this packet showed so far; TCP
// may call a dissector more than once per packet (a reassembled frame, then the rest).
struct PacketCounters {
  guint frames = 0;
  guint pieces = 0;
};

constexpr guint32 kCountersKey = 0;

PacketCounters& counters_of(packet_info* pinfo, int proto) {
  auto* c = static_cast<PacketCounters*>(p_get_proto_data(pinfo->pool, pinfo, proto, kCountersKey));
  if (c == nullptr) {
    c = new (wmem_alloc(pinfo->pool, sizeof(PacketCounters))) PacketCounters{};
    p_add_proto_data(pinfo->pool, pinfo, proto, kCountersKey, c);
  }
  return *c;
}

// The record of this packet's next frame. Records are keyed by the frame's position among the
// packet's frames, which is the same on every pass. Only the first pass makes new ones.
FrameRecord* record_for(packet_info* pinfo, int proto, bool& fresh) {
  const guint32 key = counters_of(pinfo, proto).frames++;
  fresh = false;
  auto* r = static_cast<FrameRecord*>(p_get_proto_data(wmem_file_scope(), pinfo, proto, key));
  if (r != nullptr) return r;
  if (PINFO_FD_VISITED(pinfo)) {
    return new (wmem_alloc(pinfo->pool, sizeof(FrameRecord))) FrameRecord{};
  }
  r = new_frame_record();
  r->packet = pinfo->num;
  r->time = pinfo->abs_ts;
  p_add_proto_data(wmem_file_scope(), pinfo, proto, key, r);
  fresh = true;
  return r;
}

void add_info(packet_info* pinfo, const InverterProtocol& p, const char* text) {
  PacketCounters& c = counters_of(pinfo, p.proto);
  if (c.pieces++ == 0) {
    col_set_str(pinfo->cinfo, COL_PROTOCOL, p.short_name);
    col_clear(pinfo->cinfo, COL_INFO);
    col_add_str(pinfo->cinfo, COL_INFO, text);
  } else {
    col_append_sep_str(pinfo->cinfo, COL_INFO, " | ", text);
  }
}

void ask_for_more(packet_info* pinfo, guint offset, const SegmentCut& cut, std::size_t have) {
  pinfo->desegment_offset = static_cast<int>(offset);
  pinfo->desegment_len =
      cut.length > have ? static_cast<guint32>(cut.length - have) : DESEGMENT_ONE_MORE_SEGMENT;
}

void dissect_frame(const TreeTarget& target, std::span<const std::uint8_t> bytes,
                   const SegmentCut& cut, const StreamContext& ctx) {
  bool fresh = false;
  FrameRecord* record = record_for(target.pinfo, ctx.protocol->proto, fresh);
  const FrameInput in{bytes, cut.dialect, cut.role, cut.check, ctx.hint != RoleHint::Unknown};
  const AnalysisContext actx{ctx.protocol, record, fresh ? ctx.matcher : nullptr,
                             target.pinfo->pool, target.tree != nullptr};
  FramePlan plan;
  analyze_frame(in, actx, plan);
  add_info(target.pinfo, *ctx.protocol, plan.summary);
  queue_response_time(target.pinfo, *ctx.protocol, *record);
  add_frame_tree(target, plan, *record);
}

void dissect_noise(const TreeTarget& target, std::span<const std::uint8_t> bytes) {
  // Only RTU noise can hold an RTU frame of an unknown function.
  const auto unknown =
      target.protocol->dialects.rtu() ? unknown_function_frame(bytes) : std::nullopt;
  const char* text =
      unknown ? wmem_strdup_printf(target.pinfo->pool, "frame of unknown function code 0x%02X",
                                   unknown->function)
              : wmem_strdup_printf(target.pinfo->pool, "noise (%d bytes)", target.length);
  add_info(target.pinfo, *target.protocol, text);
  add_noise_tree(target, unknown);
}

}  // namespace

int dissect_stream(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, const StreamContext& ctx) {
  const guint captured = tvb_captured_length(tvb);
  if (captured == 0) return 0;
  const auto* bytes = static_cast<const guint8*>(tvb_memdup(pinfo->pool, tvb, 0, captured));
  // Bytes cut off by the snapshot length cannot be completed by later segments.
  const bool whole = tvb_reported_length(tvb) == captured;
  const CutOptions options{ctx.hint, ctx.protocol->dialects, ctx.desegment && whole};
  guint offset = 0;
  while (offset < captured) {
    const std::span<const std::uint8_t> rest(bytes + offset, captured - offset);
    const SegmentCut cut = cut_segment(rest, options);
    if (cut.kind == SegmentCut::Kind::NeedMore) {
      ask_for_more(pinfo, offset, cut, rest.size());
      break;
    }
    if (cut.length == 0 || cut.length > rest.size()) break;  // every piece takes a byte
    const TreeTarget target{
        tvb, pinfo, tree, static_cast<int>(offset), static_cast<int>(cut.length), ctx.protocol};
    const auto piece = rest.first(cut.length);
    if (cut.kind == SegmentCut::Kind::Frame) {
      dissect_frame(target, piece, cut, ctx);
    } else {
      dissect_noise(target, piece);
    }
    offset += static_cast<guint>(cut.length);
  }
  return static_cast<int>(captured);
}

}  // namespace pvtap::dissector
