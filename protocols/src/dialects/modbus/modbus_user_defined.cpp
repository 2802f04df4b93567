#include "dialects/modbus/modbus_user_defined.h"

#include <cstddef>
#include <cstdint>

#include "pvtap/codec/checksums.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {

std::optional<FrameCandidate> user_defined_reading(std::span<const std::uint8_t> frame,
                                                   RoleHint hint, DialectSet dialects) {
  constexpr std::size_t kShortest = 4;  // station, function, CRC: a code with no data
  if (!dialects.contains(Dialect::Modbus) || frame.size() < kShortest ||
      frame.size() > kMaxRtuFrameLength || frame[0] == fc::kModbusBroadcast ||
      frame[0] > fc::kLastModbusStation || !fc::is_user_defined_function(frame[1])) {
    return std::nullopt;
  }
  // The CRC over the whole frame, its own two bytes included, is 0 when they hold.
  if (Crc16Modbus::compute(frame) != 0) return std::nullopt;
  const Role role = hint == RoleHint::Response ? Role::Response : Role::Request;
  return FrameCandidate{frame.size(), Dialect::Modbus, role, true};
}

}  // namespace pvtap::detail
