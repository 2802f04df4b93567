#include "stream/stream_dissection.h"

#include <epan/dissectors/packet-tcp.h>
#include <epan/proto_data.h>

#include <span>

#include "plan/frame_analysis.h"
#include "settings/register_decoding.h"
#include "statistics/response_time_stats.h"
#include "tree/frame_tree.h"

namespace pvtap::dissector {
namespace {

// PacketCounters: how many pieces of a protocol this packet showed so far, and how many times
// the bound protocol was called for it (TCP may call more than once per packet).
struct PacketCounters {
  guint pieces = 0;
  guint calls = 0;
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

using CallView = SegmentedBus::CallSpan;

// First pass: feeds the new bytes to the bus and notes what is decided. noexcept: the core may
// allocate, and nothing may be thrown into Wireshark.
CallView feed(std::span<const std::uint8_t> bytes, std::uint64_t from, double time,
              const StreamContext& ctx) noexcept {
  try {
    return ctx.bus->bus().show(ctx.direction, from, bytes, time, ctx.desegment);
  } catch (...) {
    return CallView{from, from};  // out of memory: show these bytes as undecided
  }
}

std::uint64_t stream_start(tvbuff_t* tvb, const StreamContext& ctx, std::size_t captured) {
  if (ctx.tcp == nullptr) return ctx.bus->next_datagram(ctx.direction, captured);
  // The bytes TCP hands over end where the segment ends, reassembled or not.
  const auto length = static_cast<guint32>(tvb_reported_length(tvb));
  return ctx.bus->stream_offset(ctx.direction, ctx.tcp->nxtseq - length);
}

const CallView* view_of_call(tvbuff_t* tvb, packet_info* pinfo, const StreamContext& ctx,
                             std::span<const std::uint8_t> bytes) {
  const int proto = ctx.protocol->proto;
  const guint32 key = 1 + counters_of(pinfo, proto).calls++;
  auto* view = static_cast<CallView*>(p_get_proto_data(wmem_file_scope(), pinfo, proto, key));
  if (view != nullptr || PINFO_FD_VISITED(pinfo)) return view;
  const std::uint64_t from = stream_start(tvb, ctx, bytes.size());
  view = new (wmem_alloc(wmem_file_scope(), sizeof(CallView)))
      CallView(feed(bytes, from, nstime_to_sec(&pinfo->abs_ts), ctx));
  p_add_proto_data(wmem_file_scope(), pinfo, proto, key, view);
  return view;
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

// The packet's pool: freed with the packet, without destructors.
Arena packet_arena(packet_info* pinfo) {
  constexpr auto allocate = [](void* pool, std::size_t size) {
    return wmem_alloc(static_cast<wmem_allocator_t*>(pool), size);
  };
  return Arena{allocate, pinfo->pool};
}

void dissect_frame(const TreeTarget& target, std::span<const std::uint8_t> bytes,
                   FrameRecord& record) {
  // The first packet to show a frame is the one its links point to.
  if (record.packet == 0) {
    record.packet = target.pinfo->num;
    record.time = {target.pinfo->abs_ts.secs, target.pinfo->abs_ts.nsecs};
  }
  const InverterProtocol& p = *target.protocol;
  AnalysisContext actx;
  actx.decoder = &register_decoder();
  actx.record = &record;
  actx.arena = packet_arena(target.pinfo);
  actx.check_word = p.check_word;
  actx.verify_check = p.settings.verify_check;
  actx.with_values = target.tree != nullptr;
  FramePlan plan;
  analyze_frame(bytes, actx, plan);
  const DescriptionContext dctx{.arena = actx.arena,
                                .length = target.length,
                                .visited = PINFO_FD_VISITED(target.pinfo) != 0,
                                .check_word = p.check_word,
                                .reply_timeout_ms = p.settings.reply_timeout_ms};
  const TreeDescription tree = describe_frame(plan, record, dctx);
  // Only now the calls that may longjmp: the plan and the tree's description are plain data.
  add_info(target.pinfo, p, plan.summary);
  queue_response_time(target.pinfo, p, record);
  add_tree(target, tree);
}

void dissect_noise(const TreeTarget& target, std::span<const std::uint8_t> bytes) {
  // Only RTU noise can hold an RTU frame of an unknown function.
  const auto unknown =
      target.protocol->dialects.rtu() ? unknown_function_frame(bytes) : std::nullopt;
  const char* text =
      unknown ? wmem_strdup_printf(target.pinfo->pool, "frame of unknown function code 0x%02X",
                                   unknown->function)
              : wmem_strdup_printf(target.pinfo->pool, "noise (%d bytes)", target.length);
  const TreeDescription tree =
      describe_noise(unknown, {.arena = packet_arena(target.pinfo), .length = target.length});
  add_info(target.pinfo, *target.protocol, text);
  add_tree(target, tree);
}

void dissect_piece(const BusPiece& piece, std::span<const std::uint8_t> bytes, guint offset,
                   tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, const StreamContext& ctx) {
  FrameRecord* record = piece.frame ? ctx.bus->record(piece.frame_id) : nullptr;
  // A frame goes to the protocol of its dialect: one gateway may carry ASCII and RTU stations.
  InverterProtocol* protocol = record != nullptr ? &protocol_of(record->dialect) : ctx.protocol;
  const TreeTarget target{
      tvb, pinfo, tree, static_cast<int>(offset), static_cast<int>(piece.length), protocol};
  if (record != nullptr) {
    dissect_frame(target, bytes, *record);
  } else {
    dissect_noise(target, bytes);
  }
}

}  // namespace

int dissect_stream(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, const StreamContext& ctx) {
  const guint captured = tvb_captured_length(tvb);
  if (captured == 0) return 0;
  const auto* data = static_cast<const guint8*>(tvb_memdup(pinfo->pool, tvb, 0, captured));
  const std::span<const std::uint8_t> bytes(data, captured);
  const CallView* view = view_of_call(tvb, pinfo, ctx, bytes);
  if (view == nullptr) return static_cast<int>(captured);
  for (const BusPiece& piece : ctx.bus->bus().pieces(ctx.direction, view->from, view->shown_to)) {
    const std::uint64_t offset = piece.offset - view->from;
    if (offset + piece.length > captured) break;
    dissect_piece(piece, bytes.subspan(offset, piece.length), static_cast<guint>(offset), tvb,
                  pinfo, tree, ctx);
  }
  if (ctx.desegment && view->shown_to < view->from + captured) {
    pinfo->desegment_offset = static_cast<int>(view->shown_to - view->from);
    pinfo->desegment_len = DESEGMENT_ONE_MORE_SEGMENT;
  }
  return static_cast<int>(captured);
}

}  // namespace pvtap::dissector
