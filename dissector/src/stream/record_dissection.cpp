#include "stream/record_dissection.h"

#include <epan/tvbuff.h>

#include <algorithm>
#include <cstring>
#include <span>

#include "columns/talker_columns.h"
#include "pvtap/codec/noise_resemblance.h"
#include "stream/call_view.h"
#include "stream/piece_display.h"

namespace pvtap::dissector {
namespace {

constexpr Direction kSerial = Direction::Unknown;  // the frames' structure tells the direction

// First pass: the waiting records whose last byte this call decided learn that it shows the
// piece holding that byte.
void complete_waiting(BusTrack& bus, const CallView& view, guint32 number) {
  for (const BusPiece& piece : bus.bus().pieces(kSerial, view.from, view.shown_to)) {
    const FrameRecord* frame = piece.frame ? bus.record(piece.frame_id) : nullptr;
    bus.waiting().complete(piece.offset + piece.length, [number, frame](CallView& waiting) {
      waiting.completed_in = number;
      waiting.completed_by = frame;
    });
  }
}

// First pass: a record whose last byte is not decided waits. Its waiting bytes are shown under
// the protocol whose frames they resemble, as noise is, decided now so that every pass agrees.
void note_waiting(BusTrack& bus, CallView& view, std::size_t length, InverterProtocol& bound) {
  const std::uint64_t end = view.record_from + length;
  if (view.decided_to >= end) return;
  const bool ascii = resembles_ascii_frame(bus.held().range(view.decided_to, end));
  view.waits_under = ascii ? &ascii_protocol() : &bound;
  bus.waiting().add(end, &view);
}

// First pass: feeds the record, notes which pieces it shows and copies the bytes they need
// from earlier records. noexcept: nothing may be thrown into Wireshark.
void feed_record(std::span<const std::uint8_t> bytes, const packet_info* pinfo, BusTrack& bus,
                 CallView& view, InverterProtocol& bound) noexcept {
  HeldBytes& held = bus.held();
  view.record_from = bus.next_datagram(kSerial, bytes.size());
  view.from = held.shown_to();
  try {
    bus.bus().show(kSerial, view.record_from, bytes, nstime_to_sec(&pinfo->abs_ts), true);
    const std::uint64_t decided = bus.bus().decided_to(kSerial);
    const std::span<const std::uint8_t> earlier = held.range(view.from, view.record_from);
    if (!earlier.empty()) {
      view.earlier = static_cast<const std::uint8_t*>(
          wmem_memdup(wmem_file_scope(), earlier.data(), earlier.size()));
    }
    held.keep(view.record_from, bytes, decided);
    view.decided_to = view.shown_to = decided;
    complete_waiting(bus, view, pinfo->num);
    note_waiting(bus, view, bytes.size(), bound);
  } catch (...) {
    view.decided_to = view.shown_to = view.from;  // out of memory: nothing shown
  }
}

// The bytes of a piece that began in an earlier record, in a buffer of the packet's pool.
std::span<const std::uint8_t> joined_bytes(const CallView& view, const BusPiece& piece,
                                           std::span<const std::uint8_t> record,
                                           packet_info* pinfo) {
  const std::uint64_t end = piece.offset + piece.length;
  const std::uint64_t from_earlier = std::min(end, view.record_from) - piece.offset;
  const std::uint64_t from_record = end - piece.offset - from_earlier;
  if (view.earlier == nullptr || from_record > record.size()) return {};
  auto* joined = static_cast<std::uint8_t*>(wmem_alloc(pinfo->pool, piece.length));
  std::memcpy(joined, view.earlier + (piece.offset - view.from), from_earlier);
  std::memcpy(joined + from_earlier, record.data(), from_record);
  return {joined, piece.length};
}

void show_joined(const CallView& view, const BusPiece& piece, std::span<const std::uint8_t> record,
                 const PieceTarget& t) {
  const std::span<const std::uint8_t> bytes = joined_bytes(view, piece, record, t.pinfo);
  if (bytes.empty()) return;
  const auto length = static_cast<guint>(bytes.size());
  tvbuff_t* joined =
      tvb_new_child_real_data(t.tvb, bytes.data(), length, static_cast<gint>(length));
  add_new_data_source(t.pinfo, joined, "Frame reassembled from serial records");
  PieceTarget target = t;
  target.tvb = joined;
  show_piece(target, piece, bytes, 0);
}

// Shows the pieces the record's call decided and notes their talkers; returns how many.
int show_record_pieces(const CallView& view, std::span<const std::uint8_t> record,
                       const PieceTarget& t, TalkerColumns& talkers) {
  int shown = 0;
  for (const BusPiece& piece : t.bus->bus().pieces(kSerial, view.from, view.shown_to)) {
    if (const FrameRecord* frame = piece.frame ? t.bus->record(piece.frame_id) : nullptr) {
      add_talkers(talkers, *frame, t.pinfo->pool);
    }
    ++shown;
    if (piece.offset < view.record_from) {
      show_joined(view, piece, record, t);
      continue;
    }
    const std::uint64_t offset = piece.offset - view.record_from;
    if (offset + piece.length > record.size()) break;
    show_piece(t, piece, record.subspan(offset, piece.length), static_cast<int>(offset));
  }
  return shown;
}

// What a record whose last byte waits is, as TCP names a segment of a reassembled PDU.
const char* waiting_text(const CallView& view, packet_info* pinfo) {
  if (view.completed_in == 0) return "part of a frame";
  return wmem_strdup_printf(pinfo->pool, "part of a %s, completed in #%u",
                            view.completed_by != nullptr ? "frame" : "noise run",
                            view.completed_in);
}

// The record's waiting bytes; a record that shows nothing else says in its columns what it
// is, and who talks once the frame that completes it is known.
void show_waiting(const CallView& view, std::span<const std::uint8_t> record, const PieceTarget& t,
                  const SerialRecordFields& f, bool alone, TalkerColumns& talkers) {
  const std::uint64_t from = std::max(view.decided_to, view.record_from);
  const auto offset = static_cast<gint>(from - view.record_from);
  const auto length = static_cast<gint>(record.size()) - offset;
  const char* text = waiting_text(view, t.pinfo);
  if (alone) {
    col_set_str(t.pinfo->cinfo, COL_PROTOCOL, view.waits_under->short_name);
    col_add_fstr(t.pinfo->cinfo, COL_INFO, "[%s]", text);
    if (view.completed_by != nullptr) add_talkers(talkers, *view.completed_by, t.pinfo->pool);
  }
  proto_item* item = proto_tree_add_item(t.tree, f.proto, t.tvb, offset, length, ENC_NA);
  proto_item_append_text(item, ": %s", text);
  proto_tree* subtree = proto_item_add_subtree(item, f.ett);
  proto_tree_add_uint(subtree, f.waiting, t.tvb, offset, length, static_cast<guint32>(length));
  if (view.completed_in != 0) {
    proto_item_set_generated(
        proto_tree_add_uint(subtree, f.completed_in, t.tvb, offset, length, view.completed_in));
  }
}

}  // namespace

int dissect_serial_record(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree,
                          InverterProtocol& protocol, BusTrack& bus,
                          const SerialRecordFields& fields) {
  const guint captured = tvb_captured_length(tvb);
  if (captured == 0) return 0;
  const auto* data = static_cast<const guint8*>(tvb_memdup(pinfo->pool, tvb, 0, captured));
  const std::span<const std::uint8_t> record(data, captured);
  const guint32 number = next_call_number(pinfo, protocol.proto);
  CallView* view = noted_view(pinfo, protocol.proto, number);
  if (view == nullptr) {
    if (PINFO_FD_VISITED(pinfo)) return static_cast<int>(captured);
    view = &note_view(pinfo, protocol.proto, number);
    feed_record(record, pinfo, bus, *view, protocol);
  }
  const PieceTarget target{tvb, pinfo, tree, &protocol, &bus};
  TalkerColumns talkers;
  const int shown = show_record_pieces(*view, record, target, talkers);
  note_timeouts(*view, pinfo, bus);
  show_timeouts(*view, tvb, pinfo, tree);
  if (view->waits_under != nullptr) {
    show_waiting(*view, record, target, fields, shown == 0 && view->timeout_count == 0, talkers);
  }
  write_talkers(talkers, pinfo);
  return static_cast<int>(captured);
}

}  // namespace pvtap::dissector
