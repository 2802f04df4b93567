#include "lan/v5_frame.h"

namespace pvtap::sim {
namespace {

void put_le32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

}  // namespace

std::vector<std::uint8_t> v5_frame(std::uint16_t control, std::uint8_t seq0, std::uint8_t seq1,
                                   std::uint32_t serial, std::span<const std::uint8_t> payload) {
  solarman_v5::Header header;
  header.control = control;
  header.sequence = static_cast<std::uint16_t>(seq0 | (unsigned{seq1} << 8));  // little endian
  header.serial = serial;
  return solarman_v5::encode_frame(header, payload);
}

std::vector<std::uint8_t> v5_response_payload(std::span<const std::uint8_t> rtu,
                                              const V5Clock& clock, std::size_t quirk) {
  std::vector<std::uint8_t> out{0x02, 0x01};
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
