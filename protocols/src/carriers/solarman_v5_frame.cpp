// Solarman V5 frames: their header, payload fields, checksum, the quirk, and their encoding.
#include "pvtap/carriers/solarman_v5_frame.h"

#include "pvtap/codec/checksums.h"
#include "pvtap/framing/framing_probe.h"

namespace pvtap::solarman_v5 {
namespace {

std::uint16_t u16_le(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint16_t>(b[at] | (b[at + 1] << 8));
}

std::uint32_t u32_le(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint32_t>(u16_le(b, at)) |
         (static_cast<std::uint32_t>(u16_le(b, at + 2)) << 16);
}

void put_u16_le(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v & 0xFF));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}

void put_u32_le(std::vector<std::uint8_t>& out, std::uint32_t v) {
  put_u16_le(out, static_cast<std::uint16_t>(v & 0xFFFF));
  put_u16_le(out, static_cast<std::uint16_t>(v >> 16));
}

bool crc_holds(std::span<const std::uint8_t> rtu) {
  // CRC-16/MODBUS over a frame with its CRC (low byte first) leaves zero.
  return rtu.size() >= 4 && Crc16Modbus::compute(rtu) == 0;
}

// Whether the structure of a response (its function code and length fields) makes it
// exactly `length` bytes long in some dialect.
bool response_reading_of(std::span<const std::uint8_t> rtu, std::size_t length) {
  const CandidateList readings =
      frame_candidates(rtu, RoleHint::Response, DialectSet::all(), Plausibility::Ignore);
  for (std::size_t i = 0; i < readings.size; ++i) {
    if (readings.items[i].length == length && !readings.items[i].needs_good_check) return true;
  }
  return false;
}

// The stick's two extra zeros. Zeros after a CRC leave its residue zero, so a CRC holds with
// them as without them and cannot tell alone: the frame's structure (function code, byte
// count) decides where it says the frame ends; else a CRC that holds without the zeros. A
// frame damaged on the line holds neither way, and its own CRC is 00 00 only once in 65,536:
// the zeros are the quirk unless its structure makes it end with them.
bool has_quirk(std::span<const std::uint8_t> rtu) {
  if (rtu.size() < 4 + kQuirkSize) return false;
  const std::size_t n = rtu.size();
  if (rtu[n - 1] != 0 || rtu[n - 2] != 0) return false;
  const bool whole = response_reading_of(rtu, n);
  if (whole && !response_reading_of(rtu, n - kQuirkSize)) return false;
  return crc_holds(rtu.first(n - kQuirkSize)) || !whole;
}

void read_times(Frame& f, std::span<const std::uint8_t> payload, std::size_t at) {
  f.total_working_time = u32_le(payload, at);
  f.power_on_time = u32_le(payload, at + 4);
  f.offset_time = u32_le(payload, at + 8);
}

// Request and response payloads: fixed fields, then the RTU frame (and the quirk).
void read_payload(Frame& f) {
  const auto payload = f.bytes.subspan(kHeaderSize, f.header.length);
  const bool request = f.kind == FrameKind::Request;
  const std::size_t fixed = request ? kRequestFixed : kResponseFixed;
  if (payload.size() < fixed) {
    f.payload_short = true;
    return;
  }
  f.frame_type = payload[0];
  if (request) {
    f.sensor_type = u16_le(payload, 1);
  } else {
    f.status = payload[1];
  }
  read_times(f, payload, request ? 3 : 2);
  f.rtu_offset = kHeaderSize + fixed;
  f.rtu_length = payload.size() - fixed;
  if (!request && f.rtu_length == kStickCodeSize) {
    f.stick_code = payload[fixed];
    f.rtu_length = 0;
    return;
  }
  if (!request && has_quirk(f.rtu())) {
    f.rtu_length -= kQuirkSize;
    f.quirk_bytes = kQuirkSize;
  }
}

}  // namespace

FrameKind kind_of(std::uint16_t code) {
  switch (code) {
    case control::kRequest:
      return FrameKind::Request;
    case control::kResponse:
      return FrameKind::Response;
    case control::kHandshake:
    case control::kDataReport:
    case control::kWifiInfo:
    case control::kHeartbeat:
    case control::kReport:
      return FrameKind::StickFrame;
    case control::kHandshake - control::kReplyOffset:
    case control::kDataReport - control::kReplyOffset:
    case control::kWifiInfo - control::kReplyOffset:
    case control::kHeartbeat - control::kReplyOffset:
    case control::kReport - control::kReplyOffset:
      return FrameKind::StickReply;
    default:
      return FrameKind::Other;
  }
}

std::uint8_t checksum_of(std::span<const std::uint8_t> frame_bytes) {
  unsigned sum = 0;
  for (std::size_t i = 1; i + kTrailerSize < frame_bytes.size(); ++i) sum += frame_bytes[i];
  return static_cast<std::uint8_t>(sum & 0xFF);
}

Header read_header(std::span<const std::uint8_t> bytes) {
  return Header{u16_le(bytes, 1), u16_le(bytes, 3), u16_le(bytes, 5), u32_le(bytes, 7)};
}

Frame parse_frame(std::span<const std::uint8_t> bytes) {
  Frame f;
  f.bytes = bytes;
  f.header = read_header(bytes);
  f.kind = kind_of(f.header.control);
  f.checksum = bytes[bytes.size() - kTrailerSize];
  f.expected_checksum = checksum_of(bytes);
  if (f.kind == FrameKind::Request || f.kind == FrameKind::Response) read_payload(f);
  return f;
}

std::vector<std::uint8_t> encode_frame(const Header& h, std::span<const std::uint8_t> payload) {
  std::vector<std::uint8_t> out{kStart};
  put_u16_le(out, static_cast<std::uint16_t>(payload.size()));
  put_u16_le(out, h.control);
  put_u16_le(out, h.sequence);
  put_u32_le(out, h.serial);
  out.insert(out.end(), payload.begin(), payload.end());
  out.push_back(0);
  out.push_back(kEnd);
  out[out.size() - kTrailerSize] = checksum_of(out);
  return out;
}

std::vector<std::uint8_t> request_payload(std::span<const std::uint8_t> rtu) {
  std::vector<std::uint8_t> out{0x02};
  put_u16_le(out, 0);
  for (int i = 0; i < 3; ++i) put_u32_le(out, 0);
  out.insert(out.end(), rtu.begin(), rtu.end());
  return out;
}

std::vector<std::uint8_t> response_payload(std::span<const std::uint8_t> rtu, bool quirk) {
  std::vector<std::uint8_t> out{0x02, 0x01};
  for (int i = 0; i < 3; ++i) put_u32_le(out, 0);
  out.insert(out.end(), rtu.begin(), rtu.end());
  if (quirk) out.insert(out.end(), kQuirkSize, 0);
  return out;
}

}  // namespace pvtap::solarman_v5
