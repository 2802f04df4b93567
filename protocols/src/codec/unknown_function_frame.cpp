#include "pvtap/codec/unknown_function_frame.h"

#include "pvtap/codec/checksums.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap {
namespace {

constexpr std::size_t kShortestFrame = 4;   // station, function, CRC
constexpr std::size_t kLongestFrame = 256;  // Modbus serial line PDU limit
constexpr std::uint8_t kLastStation = 247;

}  // namespace

std::optional<UnknownFunctionFrame> unknown_function_frame(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < kShortestFrame || bytes.size() > kLongestFrame) return std::nullopt;
  const std::uint8_t station = bytes[0];
  const std::uint8_t function = bytes[1];
  if (station == 0 || station > kLastStation || fc::rtu_dialect_of(function)) return std::nullopt;
  const auto body = bytes.first(bytes.size() - 2);
  const auto found = static_cast<std::uint16_t>(bytes[bytes.size() - 2] | (bytes.back() << 8));
  if (Crc16Modbus::compute(body) != found) return std::nullopt;
  return UnknownFunctionFrame{station, function};
}

}  // namespace pvtap
