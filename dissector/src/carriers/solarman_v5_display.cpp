#include "carriers/solarman_v5_display.h"

#include <epan/expert.h>

#include "carriers/solarman_v5_protocol.h"
#include "pvtap/carriers/solarman_v5_frame.h"
#include "registration/inverter_protocol.h"
#include "stream/stream_dissection.h"

namespace pvtap::dissector {
namespace {

namespace v5 = solarman_v5;

proto_tree* piece_tree(const V5Target& t, int offset, int length, proto_item** item) {
  SolarmanV5Protocol& p = v5_protocol();
  *item = proto_tree_add_item(t.tree, p.proto, t.tvb, offset, length, ENC_NA);
  return proto_item_add_subtree(*item, p.ett_frame);
}

void show_header(proto_tree* tree, const V5Target& t, const v5::Frame& f, int at) {
  const V5Fields& hf = v5_protocol().hf;
  proto_tree_add_uint(tree, hf.length, t.tvb, at + 1, 2, f.header.length);
  proto_tree_add_uint(tree, hf.control, t.tvb, at + 3, 2, f.header.control);
  proto_tree_add_uint(tree, hf.sequence, t.tvb, at + 5, 2, f.header.sequence);
  proto_tree_add_uint(tree, hf.serial, t.tvb, at + 7, 4, f.header.serial);
}

// Request and response payloads: fixed fields at `at` (the payload's start).
void show_fixed_fields(proto_tree* tree, const V5Target& t, const v5::Frame& f, int at) {
  const V5Fields& hf = v5_protocol().hf;
  const bool request = f.kind == v5::FrameKind::Request;
  proto_tree_add_uint(tree, hf.frame_type, t.tvb, at, 1, f.frame_type);
  if (request) {
    proto_tree_add_uint(tree, hf.sensor_type, t.tvb, at + 1, 2, f.sensor_type);
  } else {
    proto_tree_add_uint(tree, hf.status, t.tvb, at + 1, 1, f.status);
  }
  const int times = at + (request ? 3 : 2);
  proto_tree_add_uint(tree, hf.total_working_time, t.tvb, times, 4, f.total_working_time);
  proto_tree_add_uint(tree, hf.power_on_time, t.tvb, times + 4, 4, f.power_on_time);
  proto_tree_add_uint(tree, hf.offset_time, t.tvb, times + 8, 4, f.offset_time);
}

// The RTU frame goes to invrtu whole: the V5 frame pins both its ends, as a record does.
void show_rtu(proto_tree* tree, const V5Target& t, const v5::Frame& f, int at) {
  SolarmanV5Protocol& p = v5_protocol();
  const int rtu_at = at + static_cast<int>(f.rtu_offset);
  const int rtu_length = static_cast<int>(f.rtu_length);
  proto_tree_add_item(tree, p.hf.rtu, t.tvb, rtu_at, rtu_length, ENC_NA);
  if (f.quirk_bytes > 0) {
    proto_item* quirk = proto_tree_add_item(tree, p.hf.quirk, t.tvb, rtu_at + rtu_length,
                                            static_cast<int>(f.quirk_bytes), ENC_NA);
    expert_add_info(t.pinfo, quirk, &p.ei.quirk);
  }
  tvbuff_t* rtu = tvb_new_subset_length(t.tvb, rtu_at, rtu_length);
  dissect_stream(rtu, t.pinfo, t.tree,
                 StreamContext{&rtu_protocol(), &t.track->rtu(), t.direction, nullptr, false});
}

void show_payload(proto_tree* tree, const V5Target& t, const v5::Frame& f, int at) {
  SolarmanV5Protocol& p = v5_protocol();
  const int payload_at = at + static_cast<int>(v5::kHeaderSize);
  const bool modbus = f.kind == v5::FrameKind::Request || f.kind == v5::FrameKind::Response;
  if (!modbus || f.payload_short) {
    proto_item* item =
        proto_tree_add_item(tree, p.hf.payload, t.tvb, payload_at, f.header.length, ENC_NA);
    if (f.payload_short) expert_add_info(t.pinfo, item, &p.ei.payload_short);
    return;
  }
  show_fixed_fields(tree, t, f, payload_at);
  if (f.rtu_length > 0) show_rtu(tree, t, f, at);
}

void show_frame(const V5Target& t, std::span<const std::uint8_t> bytes, int at) {
  SolarmanV5Protocol& p = v5_protocol();
  const v5::Frame f = v5::parse_frame(bytes);
  proto_item* item = nullptr;
  proto_tree* tree = piece_tree(t, at, static_cast<int>(bytes.size()), &item);
  const char* name = v5_control_name(f.header.control);
  proto_item_append_text(item, ", %s, logger %u", name, f.header.serial);
  col_add_fstr(t.pinfo->cinfo, COL_INFO, "V5 %s, logger %u", name, f.header.serial);
  show_header(tree, t, f, at);
  const auto checksum_at = static_cast<guint>(at) + static_cast<guint>(bytes.size()) - 2;
  proto_tree_add_checksum(tree, t.tvb, checksum_at, p.hf.checksum, p.hf.checksum_status,
                          &p.ei.bad_checksum, t.pinfo, f.expected_checksum, ENC_NA,
                          PROTO_CHECKSUM_VERIFY);
  show_payload(tree, t, f, at);
}

void show_run(const V5Target& t, const V5Piece& piece, int at) {
  SolarmanV5Protocol& p = v5_protocol();
  proto_item* item = nullptr;
  proto_tree* tree = piece_tree(t, at, static_cast<int>(piece.length), &item);
  const int length = static_cast<int>(piece.length);
  if (piece.kind == v5::Event::Kind::Noise) {
    expert_add_info(t.pinfo, proto_tree_add_item(tree, p.hf.noise, t.tvb, at, length, ENC_NA),
                    &p.ei.noise);
    return;
  }
  proto_item* broken = proto_tree_add_item(tree, p.hf.broken, t.tvb, at, length, ENC_NA);
  proto_tree_add_uint(tree, p.hf.claimed_length, t.tvb, at + 1, 2, piece.claimed_size);
  const bool truncated = piece.broken == v5::Broken::Truncated;
  expert_add_info(t.pinfo, broken, truncated ? &p.ei.truncated : &p.ei.length_mismatch);
}

}  // namespace

void show_v5_piece(const V5Target& t, const V5Piece& piece, std::span<const std::uint8_t> bytes,
                   int offset) {
  if (piece.kind == v5::Event::Kind::Frame) {
    show_frame(t, bytes, offset);
  } else {
    show_run(t, piece, offset);
  }
}

}  // namespace pvtap::dissector
