#include "carriers/solarman_v5_display.h"

#include <epan/expert.h>

#include "carriers/solarman_v5_protocol.h"
#include "protocol/inverter_protocol.h"
#include "pvtap/carriers/solarman_v5_frame.h"
#include "pvtap/carriers/solarman_v5_pairing.h"
#include "stream/piece_display.h"

namespace pvtap::dissector {
namespace {

namespace v5 = solarman_v5;

proto_tree* piece_tree(const V5Target& t, int offset, int length, proto_item** item) {
  SolarmanV5Protocol& p = v5_protocol();
  *item = proto_tree_add_item(t.tree, p.proto, t.tvb, offset, length, ENC_NA);
  return proto_item_add_subtree(*item, p.ett_frame);
}

void show_header(proto_tree* tree, const V5Target& t, const v5::Frame& f, int at) {
  const SolarmanV5Protocol& p = v5_protocol();
  proto_tree_add_uint(tree, p.field(V5Field::Length), t.tvb, at + 1, 2, f.header.length);
  proto_tree_add_uint(tree, p.field(V5Field::Control), t.tvb, at + 3, 2, f.header.control);
  proto_tree_add_uint(tree, p.field(V5Field::Sequence), t.tvb, at + 5, 2, f.header.sequence);
  proto_tree_add_uint(tree, p.field(V5Field::Serial), t.tvb, at + 7, 4, f.header.serial);
}

// Request and response payloads: fixed fields at `at` (the payload's start).
void show_fixed_fields(proto_tree* tree, const V5Target& t, const v5::Frame& f, int at) {
  const SolarmanV5Protocol& p = v5_protocol();
  const bool request = f.kind == v5::FrameKind::Request;
  proto_tree_add_uint(tree, p.field(V5Field::FrameType), t.tvb, at, 1, f.frame_type);
  if (request) {
    proto_tree_add_uint(tree, p.field(V5Field::SensorType), t.tvb, at + 1, 2, f.sensor_type);
  } else {
    proto_tree_add_uint(tree, p.field(V5Field::Status), t.tvb, at + 1, 1, f.status);
  }
  const int times = at + (request ? 3 : 2);
  proto_tree_add_uint(tree, p.field(V5Field::TotalWorkingTime), t.tvb, times, 4,
                      f.total_working_time);
  proto_tree_add_uint(tree, p.field(V5Field::PowerOnTime), t.tvb, times + 4, 4, f.power_on_time);
  proto_tree_add_uint(tree, p.field(V5Field::OffsetTime), t.tvb, times + 8, 4, f.offset_time);
}

// The RTU frame goes to invrtu whole (the V5 frame pins both its ends), with the verdicts of
// the bus once the pairing handed it on; until then (a request waiting for its response, in a
// first pass) with what it says of itself.
void show_rtu(proto_tree* tree, const V5Target& t, const v5::Frame& f, const V5Piece& piece,
              int at) {
  SolarmanV5Protocol& p = v5_protocol();
  const int rtu_at = at + static_cast<int>(f.rtu_offset);
  const int rtu_length = static_cast<int>(f.rtu_length);
  proto_tree_add_item(tree, p.field(V5Field::Rtu), t.tvb, rtu_at, rtu_length, ENC_NA);
  if (f.quirk_bytes > 0) {
    proto_item* quirk =
        proto_tree_add_item(tree, p.field(V5Field::Quirk), t.tvb, rtu_at + rtu_length,
                            static_cast<int>(f.quirk_bytes), ENC_NA);
    expert_add_info(t.pinfo, quirk, p.expert(V5Expert::Quirk));
  }
  if (piece.rtu == nullptr) return;
  const auto rtu = f.rtu();
  if (piece.rtu->pieces.empty()) {
    if (piece.rtu->refused || piece.rtu->other_serial) return;
    FrameRecord& own = *piece.rtu->own;
    show_frame(TreeTarget{t.tvb, t.pinfo, t.tree, rtu_at, rtu_length, &protocol_of(own.dialect)},
               rtu, own);
    return;
  }
  for (const RtuPiece& part : piece.rtu->pieces) {
    if (part.offset + part.length > rtu.size()) break;
    const auto bytes = rtu.subspan(part.offset, part.length);
    const int offset = rtu_at + static_cast<int>(part.offset);
    const int length = static_cast<int>(part.length);
    if (part.record != nullptr) {
      show_frame(
          TreeTarget{t.tvb, t.pinfo, t.tree, offset, length, &protocol_of(part.record->dialect)},
          bytes, *part.record);
    } else {
      show_noise(TreeTarget{t.tvb, t.pinfo, t.tree, offset, length, &rtu_protocol()}, bytes);
    }
  }
}

// A stick's code in place of an RTU frame: a carrier finding, never bus bytes.
void show_stick_code(proto_tree* tree, const V5Target& t, const v5::Frame& f, const V5Piece& piece,
                     int at) {
  SolarmanV5Protocol& p = v5_protocol();
  const int code_at = at + static_cast<int>(f.rtu_offset);
  proto_item* item = proto_tree_add_uint(tree, p.field(V5Field::StickCode), t.tvb, code_at,
                                         static_cast<int>(v5::kStickCodeSize), *f.stick_code);
  using Kind = v5::Release::Kind;
  if (piece.code_meaning == Kind::NoReply) {
    expert_add_info_format(t.pinfo, item, p.expert(V5Expert::StickNoReply),
                           "%s: no reply from the bus behind it (a timeout)",
                           v5::no_reply_reason(*f.stick_code).c_str());
  } else if (piece.code_meaning == Kind::Refused) {
    expert_add_info_format(t.pinfo, item, p.expert(V5Expert::StickRefused),
                           "The stick refused it: %s",
                           v5::describe_refusal(piece.addressed_serial, f.header.serial).c_str());
  } else {
    expert_add_info_format(t.pinfo, item, p.expert(V5Expert::StickCode),
                           "The stick answered code %02x", *f.stick_code);
  }
}

void show_payload(proto_tree* tree, const V5Target& t, const v5::Frame& f, const V5Piece& piece,
                  int at) {
  SolarmanV5Protocol& p = v5_protocol();
  const int payload_at = at + static_cast<int>(v5::kHeaderSize);
  const bool modbus = f.kind == v5::FrameKind::Request || f.kind == v5::FrameKind::Response;
  if (!modbus || f.payload_short) {
    proto_item* item = proto_tree_add_item(tree, p.field(V5Field::Payload), t.tvb, payload_at,
                                           f.header.length, ENC_NA);
    if (f.payload_short) expert_add_info(t.pinfo, item, p.expert(V5Expert::PayloadShort));
    return;
  }
  show_fixed_fields(tree, t, f, payload_at);
  if (f.stick_code) show_stick_code(tree, t, f, piece, at);
  if (f.rtu_length > 0) show_rtu(tree, t, f, piece, at);
}

void show_v5_frame(const V5Target& t, const V5Piece& piece, std::span<const std::uint8_t> bytes,
                   int at) {
  SolarmanV5Protocol& p = v5_protocol();
  const v5::Frame f = v5::parse_frame(bytes);
  proto_item* item = nullptr;
  proto_tree* tree = piece_tree(t, at, static_cast<int>(bytes.size()), &item);
  const char* name = v5_control_name(f.header.control);
  proto_item_append_text(item, ", %s, logger %u", name, f.header.serial);
  col_add_fstr(t.pinfo->cinfo, COL_INFO, "V5 %s, logger %u", name, f.header.serial);
  show_header(tree, t, f, at);
  const auto checksum_at = static_cast<guint>(at) + static_cast<guint>(bytes.size()) - 2;
  proto_tree_add_checksum(tree, t.tvb, checksum_at, p.field(V5Field::Checksum),
                          p.field(V5Field::ChecksumStatus), p.expert(V5Expert::BadChecksum),
                          t.pinfo, f.expected_checksum, ENC_NA, PROTO_CHECKSUM_VERIFY);
  show_payload(tree, t, f, piece, at);
}

void show_run(const V5Target& t, const V5Piece& piece, int at) {
  SolarmanV5Protocol& p = v5_protocol();
  proto_item* item = nullptr;
  proto_tree* tree = piece_tree(t, at, static_cast<int>(piece.length), &item);
  const int length = static_cast<int>(piece.length);
  if (piece.kind == v5::Event::Kind::Noise) {
    expert_add_info(t.pinfo,
                    proto_tree_add_item(tree, p.field(V5Field::Noise), t.tvb, at, length, ENC_NA),
                    p.expert(V5Expert::Noise));
    return;
  }
  proto_item* broken =
      proto_tree_add_item(tree, p.field(V5Field::Broken), t.tvb, at, length, ENC_NA);
  proto_tree_add_uint(tree, p.field(V5Field::ClaimedLength), t.tvb, at + 1, 2, piece.claimed_size);
  const bool truncated = piece.broken == v5::Broken::Truncated;
  expert_add_info(t.pinfo, broken,
                  truncated ? p.expert(V5Expert::Truncated) : p.expert(V5Expert::LengthMismatch));
}

}  // namespace

void show_v5_piece(const V5Target& t, const V5Piece& piece, std::span<const std::uint8_t> bytes,
                   int offset) {
  if (piece.kind == v5::Event::Kind::Frame) {
    show_v5_frame(t, piece, bytes, offset);
  } else {
    show_run(t, piece, offset);
  }
}

}  // namespace pvtap::dissector
