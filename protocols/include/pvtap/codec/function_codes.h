// Function codes of the three dialects as they appear on the wire.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "pvtap/codec/dialect.h"

namespace pvtap::fc {

inline constexpr std::uint8_t kAsciiRead = 0x52;  // 'R', sent as the raw character

inline constexpr std::uint8_t kHybridDeviceInfo = 0x11;
inline constexpr std::uint8_t kHybridRunningData = 0x12;
inline constexpr std::uint8_t kHybridSettings = 0x16;
inline constexpr std::uint8_t kHybridManufacturer = 0x17;
inline constexpr std::uint8_t kHybridWriteParameter = 0x18;
inline constexpr std::uint8_t kHybridRestoreFactory = 0x1F;
inline constexpr std::uint8_t kHybridError = 0xFF;  // reply only

inline constexpr std::uint8_t kGslReadHolding = 0x03;
inline constexpr std::uint8_t kGslReadInput = 0x04;
inline constexpr std::uint8_t kGslWriteSingle = 0x06;
inline constexpr std::uint8_t kGslWriteMultiple = 0x10;
inline constexpr std::uint8_t kExceptionFlag = 0x80;

inline constexpr std::uint8_t kHybridBroadcast = 0xFF;

// Which RTU dialect owns a function code (exceptions included); nullopt if neither.
constexpr std::optional<Dialect> rtu_dialect_of(std::uint8_t f) {
  switch (f) {
    case kHybridDeviceInfo:
    case kHybridRunningData:
    case kHybridSettings:
    case kHybridManufacturer:
    case kHybridWriteParameter:
    case kHybridRestoreFactory:
    case kHybridError:
      return Dialect::Hybrid;
    case kGslReadHolding:
    case kGslReadInput:
    case kGslWriteSingle:
    case kGslWriteMultiple:
    case kGslReadHolding | kExceptionFlag:
    case kGslReadInput | kExceptionFlag:
    case kGslWriteSingle | kExceptionFlag:
    case kGslWriteMultiple | kExceptionFlag:
      return Dialect::Gsl;
    default:
      return std::nullopt;
  }
}

constexpr bool is_gsl_exception(std::uint8_t f) {
  return (f & kExceptionFlag) != 0 && f != kHybridError;
}

// A short human name for a function code of a dialect ("read running data").
std::string_view function_name(Dialect d, std::uint8_t f);

// The text of a GSL exception code ("address (ID) out of range").
std::string_view exception_name(std::uint8_t code);

}  // namespace pvtap::fc
