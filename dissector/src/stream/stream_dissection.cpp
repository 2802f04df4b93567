#include "stream/stream_dissection.h"

#include <epan/dissectors/packet-tcp.h>
#include <epan/proto_data.h>

#include <span>
#include <vector>

#include "plan/frame_analysis.h"
#include "pvtap/codec/noise_resemblance.h"
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

using CallSpan = SegmentedBus::CallSpan;

// CallView: what one call shows, the same on every pass. Lives in wmem file scope.
struct CallView {
  std::uint64_t from = 0;
  std::uint64_t decided_to = 0;      // the bytes after it are handed back to TCP
  std::uint64_t shown_to = 0;        // the pieces in [from, shown_to) are this call's to show
  bool extends_pdu = false;          // a call later passes do not make (see extends_pdu)
  FrameRecord** timeouts = nullptr;  // the timeouts this call announces
  std::uint32_t timeout_count = 0;
};

// First pass: feeds the new bytes to the bus and notes what is decided. noexcept: the core may
// allocate, and nothing may be thrown into Wireshark.
CallSpan feed(std::span<const std::uint8_t> bytes, std::uint64_t from, double time,
              const StreamContext& ctx) noexcept {
  try {
    return ctx.bus->bus().show(ctx.direction, from, bytes, time, ctx.desegment);
  } catch (...) {
    return CallSpan{from, from, from};  // out of memory: show these bytes as undecided
  }
}

// Asked for more from within the bytes it handed again (the offset at most the old length),
// TCP extends the PDU it was reassembling instead of starting a new one: this call is then not
// made in later passes, so it shows nothing, and the call that completes the PDU shows what
// this one decided. A first pass so shows each piece once, where a later pass shows it.
bool extends_pdu(const CallSpan& s, std::uint64_t end, const StreamContext& ctx) {
  return ctx.desegment && s.shown_to < end && s.shown_to <= s.handed_to;
}

std::uint64_t stream_start(tvbuff_t* tvb, const StreamContext& ctx, std::size_t captured) {
  if (ctx.tcp == nullptr) return ctx.bus->next_datagram(ctx.direction, captured);
  // The bytes TCP hands over end where the segment ends, reassembled or not.
  const auto length = static_cast<guint32>(tvb_reported_length(tvb));
  return ctx.bus->stream_offset(ctx.direction, ctx.tcp->nxtseq - length);
}

CallView* view_of_call(tvbuff_t* tvb, packet_info* pinfo, const StreamContext& ctx,
                       std::span<const std::uint8_t> bytes) {
  const int proto = ctx.protocol->proto;
  const guint32 key = 1 + counters_of(pinfo, proto).calls++;
  auto* view = static_cast<CallView*>(p_get_proto_data(wmem_file_scope(), pinfo, proto, key));
  if (view != nullptr || PINFO_FD_VISITED(pinfo)) return view;
  const std::uint64_t from = stream_start(tvb, ctx, bytes.size());
  const CallSpan span = feed(bytes, from, nstime_to_sec(&pinfo->abs_ts), ctx);
  view = new (wmem_alloc(wmem_file_scope(), sizeof(CallView))) CallView{};
  view->from = from;
  view->decided_to = span.shown_to;
  view->extends_pdu = extends_pdu(span, from + bytes.size(), ctx);
  view->shown_to = view->extends_pdu ? view->from : span.shown_to;
  p_add_proto_data(wmem_file_scope(), pinfo, proto, key, view);
  return view;
}

// The timeouts not announced yet. noexcept: nothing may be thrown into Wireshark.
std::vector<FrameRecord*> unannounced(const StreamContext& ctx) noexcept {
  try {
    return ctx.bus->take_timeouts();
  } catch (...) {
    return {};  // out of memory: a later call announces them
  }
}

// First pass, once the call's pieces are shown: the timeouts it announces (none when a later
// pass will not make the call).
void note_timeouts(CallView& view, packet_info* pinfo, const StreamContext& ctx) {
  if (PINFO_FD_VISITED(pinfo) || view.extends_pdu) return;
  const std::vector<FrameRecord*> ready = unannounced(ctx);
  if (ready.empty()) return;
  view.timeouts = wmem_alloc_array(wmem_file_scope(), FrameRecord*, ready.size());
  view.timeout_count = static_cast<std::uint32_t>(ready.size());
  for (std::size_t i = 0; i < ready.size(); ++i) {
    view.timeouts[i] = ready[i];
    ready[i]->announced_in = pinfo->num;
  }
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
  add_info(target.pinfo, p,
           record.duplicate ? wmem_strdup_printf(target.pinfo->pool, "%s (duplicate)", plan.summary)
                            : plan.summary);
  queue_response_time(target.pinfo, p, record);
  add_tree(target, tree);
}

// Noise goes to the protocol whose frames it resembles: a damaged ASCII frame to invascii,
// anything else to the conversation's protocol. Only RTU noise can hold an RTU frame of an
// unknown function.
void dissect_noise(TreeTarget target, std::span<const std::uint8_t> bytes) {
  const auto unknown =
      target.protocol->dialects.rtu() ? unknown_function_frame(bytes) : std::nullopt;
  if (!unknown && resembles_ascii_frame(bytes)) target.protocol = &ascii_protocol();
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

// A timeout under the protocol of its request's dialect, as an item of its own.
void dissect_timeout(const FrameRecord& request, tvbuff_t* tvb, packet_info* pinfo,
                     proto_tree* tree) {
  InverterProtocol& p = protocol_of(request.dialect);
  const DescriptionContext dctx{.arena = packet_arena(pinfo),
                                .visited = PINFO_FD_VISITED(pinfo) != 0,
                                .check_word = p.check_word,
                                .reply_timeout_ms = p.settings.reply_timeout_ms};
  const TreeDescription description = describe_timeout(request, dctx);
  add_info(pinfo, p, wmem_strdup_printf(pinfo->pool, "no reply to frame %u", request.packet));
  add_tree(TreeTarget{tvb, pinfo, tree, 0, 0, &p}, description);
}

void show_pieces(const CallView& view, std::span<const std::uint8_t> bytes, tvbuff_t* tvb,
                 packet_info* pinfo, proto_tree* tree, const StreamContext& ctx) {
  for (const BusPiece& piece : ctx.bus->bus().pieces(ctx.direction, view.from, view.shown_to)) {
    const std::uint64_t offset = piece.offset - view.from;
    if (offset + piece.length > bytes.size()) break;
    dissect_piece(piece, bytes.subspan(offset, piece.length), static_cast<guint>(offset), tvb,
                  pinfo, tree, ctx);
  }
}

}  // namespace

int dissect_stream(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, const StreamContext& ctx) {
  const guint captured = tvb_captured_length(tvb);
  if (captured == 0) return 0;
  const auto* data = static_cast<const guint8*>(tvb_memdup(pinfo->pool, tvb, 0, captured));
  const std::span<const std::uint8_t> bytes(data, captured);
  CallView* view = view_of_call(tvb, pinfo, ctx, bytes);
  if (view == nullptr) return static_cast<int>(captured);
  show_pieces(*view, bytes, tvb, pinfo, tree, ctx);
  note_timeouts(*view, pinfo, ctx);
  for (std::uint32_t i = 0; i < view->timeout_count; ++i) {
    dissect_timeout(*view->timeouts[i], tvb, pinfo, tree);
  }
  if (ctx.desegment && view->decided_to < view->from + captured) {
    pinfo->desegment_offset = static_cast<int>(view->decided_to - view->from);
    pinfo->desegment_len = DESEGMENT_ONE_MORE_SEGMENT;
  }
  return static_cast<int>(captured);
}

}  // namespace pvtap::dissector
