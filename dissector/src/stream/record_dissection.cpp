#include "stream/record_dissection.h"

#include <epan/tvbuff.h>

#include <algorithm>
#include <cstring>
#include <span>

#include "stream/call_view.h"
#include "stream/piece_display.h"

namespace pvtap::dissector {
namespace {

constexpr Direction kSerial = Direction::Unknown;  // the frames' structure tells the direction

// First pass: feeds the record, notes which pieces it shows and copies the bytes they need
// from earlier records. noexcept: nothing may be thrown into Wireshark.
void feed_record(std::span<const std::uint8_t> bytes, double time, BusTrack& bus,
                 CallView& view) noexcept {
  HeldBytes& held = bus.held();
  view.record_from = bus.next_datagram(kSerial, bytes.size());
  view.from = held.shown_to();
  try {
    bus.bus().show(kSerial, view.record_from, bytes, time, true);
    const std::uint64_t decided = bus.bus().decided_to(kSerial);
    const std::span<const std::uint8_t> earlier = held.range(view.from, view.record_from);
    if (!earlier.empty()) {
      view.earlier = static_cast<const std::uint8_t*>(
          wmem_memdup(wmem_file_scope(), earlier.data(), earlier.size()));
    }
    held.keep(view.record_from, bytes, decided);
    view.decided_to = view.shown_to = decided;
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

void show_record_pieces(const CallView& view, std::span<const std::uint8_t> record,
                        const PieceTarget& t) {
  for (const BusPiece& piece : t.bus->bus().pieces(kSerial, view.from, view.shown_to)) {
    if (piece.offset < view.record_from) {
      show_joined(view, piece, record, t);
      continue;
    }
    const std::uint64_t offset = piece.offset - view.record_from;
    if (offset + piece.length > record.size()) break;
    show_piece(t, piece, record.subspan(offset, piece.length), static_cast<int>(offset));
  }
}

}  // namespace

int dissect_serial_record(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree,
                          InverterProtocol& protocol, BusTrack& bus) {
  const guint captured = tvb_captured_length(tvb);
  if (captured == 0) return 0;
  const auto* data = static_cast<const guint8*>(tvb_memdup(pinfo->pool, tvb, 0, captured));
  const std::span<const std::uint8_t> record(data, captured);
  const guint32 number = next_call_number(pinfo, protocol.proto);
  CallView* view = noted_view(pinfo, protocol.proto, number);
  if (view == nullptr) {
    if (PINFO_FD_VISITED(pinfo)) return static_cast<int>(captured);
    view = &note_view(pinfo, protocol.proto, number);
    feed_record(record, nstime_to_sec(&pinfo->abs_ts), bus, *view);
  }
  show_record_pieces(*view, record, PieceTarget{tvb, pinfo, tree, &protocol, &bus});
  note_timeouts(*view, pinfo, bus);
  show_timeouts(*view, tvb, pinfo, tree);
  return static_cast<int>(captured);
}

}  // namespace pvtap::dissector
