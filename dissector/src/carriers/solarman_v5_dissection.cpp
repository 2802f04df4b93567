#include "carriers/solarman_v5_dissection.h"

#include <epan/dissectors/packet-tcp.h>

#include "carriers/solarman_v5_display.h"
#include "carriers/solarman_v5_protocol.h"
#include "stream/call_view.h"
#include "stream/piece_display.h"

namespace pvtap::dissector {
namespace {

using CallSpan = SegmentedBus::CallSpan;

// First pass: feeds the new bytes to the reader. noexcept: nothing may be thrown into
// Wireshark.
CallSpan feed(std::span<const std::uint8_t> bytes, std::uint64_t from, double time,
              const V5Context& ctx) noexcept {
  try {
    return ctx.track->show(ctx.direction, from, bytes, time, ctx.desegment);
  } catch (...) {
    return CallSpan{from, from, from};  // out of memory: show these bytes as undecided
  }
}

// As for invrtu's stream (stream_dissection.cpp): a call TCP makes only to extend the PDU it
// reassembles shows nothing, so a first pass shows each piece where a later pass does.
bool extends_pdu(const CallSpan& s, std::uint64_t end, const V5Context& ctx) {
  return ctx.desegment && s.shown_to < end && s.shown_to <= s.handed_to;
}

CallView* view_of_call(tvbuff_t* tvb, packet_info* pinfo, const V5Context& ctx,
                       std::span<const std::uint8_t> bytes) {
  const int proto = v5_protocol().proto;
  const guint32 number = next_call_number(pinfo, proto);
  CallView* noted = noted_view(pinfo, proto, number);
  if (noted != nullptr || PINFO_FD_VISITED(pinfo)) return noted;
  const auto length = static_cast<guint32>(tvb_reported_length(tvb));
  const std::uint64_t from =
      ctx.track->offsets().stream_offset(ctx.direction, ctx.tcp->nxtseq - length);
  const CallSpan span = feed(bytes, from, nstime_to_sec(&pinfo->abs_ts), ctx);
  CallView& view = note_view(pinfo, proto, number);
  view.from = from;
  view.decided_to = span.shown_to;
  view.extends_pdu = extends_pdu(span, from + bytes.size(), ctx);
  view.shown_to = view.extends_pdu ? view.from : span.shown_to;
  return &view;
}

}  // namespace

int dissect_v5_stream(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, const V5Context& ctx) {
  const guint captured = tvb_captured_length(tvb);
  if (captured == 0 || ctx.tcp == nullptr) return 0;
  const auto* data = static_cast<const guint8*>(tvb_memdup(pinfo->pool, tvb, 0, captured));
  const std::span<const std::uint8_t> bytes(data, captured);
  CallView* view = view_of_call(tvb, pinfo, ctx, bytes);
  if (view == nullptr) return static_cast<int>(captured);
  col_set_str(pinfo->cinfo, COL_PROTOCOL, "invV5");
  const V5Target target{tvb, pinfo, tree, ctx.track, ctx.direction};
  for (const V5Piece& piece : ctx.track->pieces(ctx.direction, view->from, view->shown_to)) {
    const std::uint64_t offset = piece.offset - view->from;
    if (offset + piece.length > bytes.size()) break;
    show_v5_piece(target, piece, bytes.subspan(offset, piece.length), static_cast<int>(offset));
  }
  // The timeouts the RTU frames shown made due, announced by the call that showed them.
  if (!PINFO_FD_VISITED(pinfo) && !view->extends_pdu && view->timeouts == nullptr) {
    view->timeouts = announce_timeouts(pinfo, ctx.track->timeouts(), view->timeout_count);
  }
  show_timeouts(*view, tvb, pinfo, tree);
  if (ctx.desegment && view->decided_to < view->from + captured) {
    pinfo->desegment_offset = static_cast<int>(view->decided_to - view->from);
    pinfo->desegment_len = DESEGMENT_ONE_MORE_SEGMENT;
  }
  return static_cast<int>(captured);
}

}  // namespace pvtap::dissector
