#include "stream/stream_dissection.h"

#include <epan/dissectors/packet-tcp.h>

#include <span>

#include "columns/talker_columns.h"
#include "stream/call_view.h"
#include "stream/piece_display.h"

namespace pvtap::dissector {
namespace {

using CallSpan = SegmentedBus::CallSpan;

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
  const guint32 number = next_call_number(pinfo, proto);
  CallView* noted = noted_view(pinfo, proto, number);
  if (noted != nullptr || PINFO_FD_VISITED(pinfo)) return noted;
  const std::uint64_t from = stream_start(tvb, ctx, bytes.size());
  const CallSpan span = feed(bytes, from, nstime_to_sec(&pinfo->abs_ts), ctx);
  CallView& view = note_view(pinfo, proto, number);
  view.from = from;
  view.decided_to = span.shown_to;
  view.extends_pdu = extends_pdu(span, from + bytes.size(), ctx);
  view.shown_to = view.extends_pdu ? view.from : span.shown_to;
  return &view;
}

void show_pieces(const CallView& view, std::span<const std::uint8_t> bytes, const PieceTarget& t,
                 const StreamContext& ctx, TalkerColumns& talkers) {
  for (const BusPiece& piece : ctx.bus->bus().pieces(ctx.direction, view.from, view.shown_to)) {
    const FrameRecord* frame = piece.frame ? ctx.bus->record(piece.frame_id) : nullptr;
    if (frame != nullptr && ctx.names_talkers) add_talkers(talkers, *frame, t.pinfo->pool);
    const std::uint64_t offset = piece.offset - view.from;
    if (offset + piece.length > bytes.size()) break;
    show_piece(t, piece, bytes.subspan(offset, piece.length), static_cast<int>(offset));
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
  TalkerColumns talkers;
  show_pieces(*view, bytes, PieceTarget{tvb, pinfo, tree, ctx.protocol, ctx.bus}, ctx, talkers);
  note_timeouts(*view, pinfo, *ctx.bus);
  show_timeouts(*view, tvb, pinfo, tree);
  write_talkers(talkers, pinfo);
  if (ctx.desegment && view->decided_to < view->from + captured) {
    pinfo->desegment_offset = static_cast<int>(view->decided_to - view->from);
    pinfo->desegment_len = DESEGMENT_ONE_MORE_SEGMENT;
  }
  return static_cast<int>(captured);
}

}  // namespace pvtap::dissector
