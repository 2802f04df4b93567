#include "lan/v5_frame.h"

#include <algorithm>

namespace pvtap::sim {
namespace {

void put_le16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}

void put_le32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

}  // namespace

std::uint8_t v5_checksum(std::span<const std::uint8_t> frame) {
  unsigned sum = 0;
  for (std::size_t i = 1; i + 2 < frame.size(); ++i) sum += frame[i];
  return static_cast<std::uint8_t>(sum);
}

std::vector<std::uint8_t> v5_frame(std::uint16_t control, std::uint8_t seq0, std::uint8_t seq1,
                                   std::uint32_t serial, std::span<const std::uint8_t> payload) {
  std::vector<std::uint8_t> out;
  out.reserve(kV5Overhead + payload.size());
  out.push_back(0xA5);
  put_le16(out, static_cast<std::uint16_t>(payload.size()));
  put_le16(out, control);
  out.push_back(seq0);
  out.push_back(seq1);
  put_le32(out, serial);
  out.insert(out.end(), payload.begin(), payload.end());
  out.push_back(0);  // the checksum, once the bytes before it are in place
  out.push_back(0x15);
  out[out.size() - 2] = v5_checksum(out);
  return out;
}

std::vector<std::uint8_t> v5_request_payload(std::span<const std::uint8_t> rtu) {
  // Frame type, sensor type and the times take 15 bytes.
  std::vector<std::uint8_t> out(15 + rtu.size(), 0);
  out[0] = 0x02;
  std::copy(rtu.begin(), rtu.end(), out.begin() + 15);
  return out;
}

std::vector<std::uint8_t> v5_response_payload(std::span<const std::uint8_t> rtu,
                                              const V5Clock& clock, std::size_t quirk) {
  std::vector<std::uint8_t> out;
  out.reserve(14 + rtu.size() + quirk);
  out.push_back(0x02);
  out.push_back(0x01);
  put_le32(out, clock.total_working_s);
  put_le32(out, clock.power_on_s);
  put_le32(out, clock.offset_s);
  out.insert(out.end(), rtu.begin(), rtu.end());
  out.resize(out.size() + quirk, 0);
  return out;
}

std::vector<std::uint8_t> v5_answer_payload(std::uint8_t frame_type, std::uint32_t unix_s) {
  std::vector<std::uint8_t> out;
  out.push_back(frame_type);
  out.push_back(0x01);
  put_le32(out, unix_s);
  put_le32(out, 0);
  return out;
}

}  // namespace pvtap::sim
