// Function codes of the dialects as they appear on the wire.
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

// The public Modbus function codes (PROTOCOLS.md section 6). GSL uses 0x03 0x04 0x06 0x10.
inline constexpr std::uint8_t kReadCoils = 0x01;
inline constexpr std::uint8_t kReadDiscreteInputs = 0x02;
inline constexpr std::uint8_t kGslReadHolding = 0x03;
inline constexpr std::uint8_t kGslReadInput = 0x04;
inline constexpr std::uint8_t kWriteSingleCoil = 0x05;
inline constexpr std::uint8_t kGslWriteSingle = 0x06;
inline constexpr std::uint8_t kReadExceptionStatus = 0x07;
inline constexpr std::uint8_t kDiagnostics = 0x08;
inline constexpr std::uint8_t kCommEventCounter = 0x0B;
inline constexpr std::uint8_t kCommEventLog = 0x0C;
inline constexpr std::uint8_t kWriteMultipleCoils = 0x0F;
inline constexpr std::uint8_t kGslWriteMultiple = 0x10;
inline constexpr std::uint8_t kReportServerId = 0x11;
inline constexpr std::uint8_t kReadFileRecord = 0x14;
inline constexpr std::uint8_t kWriteFileRecord = 0x15;
inline constexpr std::uint8_t kMaskWriteRegister = 0x16;
inline constexpr std::uint8_t kReadWriteMultiple = 0x17;
inline constexpr std::uint8_t kReadFifoQueue = 0x18;
inline constexpr std::uint8_t kEncapsulatedInterface = 0x2B;
inline constexpr std::uint8_t kMeiDeviceIdentification = 0x0E;
inline constexpr std::uint8_t kExceptionFlag = 0x80;
// The gateway exception codes: no path to the target, and a target that did not answer.
inline constexpr std::uint8_t kGatewayPathUnavailable = 0x0A;
inline constexpr std::uint8_t kGatewayTargetNoResponse = 0x0B;

inline constexpr std::uint8_t kHybridBroadcast = 0xFF;
inline constexpr std::uint8_t kModbusBroadcast = 0x00;
inline constexpr std::uint8_t kLastModbusStation = 247;

// Hybrid reads: their replies carry the data of the count registers asked for.
constexpr bool is_hybrid_read(std::uint8_t f) {
  return f == kHybridDeviceInfo || f == kHybridRunningData || f == kHybridSettings ||
         f == kHybridManufacturer;
}

// Hybrid requests that name a start and a count: the reads, and restore factory settings.
constexpr bool is_hybrid_range_request(std::uint8_t f) {
  return is_hybrid_read(f) || f == kHybridRestoreFactory;
}

// An exception reply of the Modbus family: fc|0x80 (Hybrid's 0xFF error reply is not one).
constexpr bool is_gsl_exception(std::uint8_t f) {
  return (f & kExceptionFlag) != 0 && f != kHybridError;
}

// The user-defined codes of the Modbus specification (no public length rule).
constexpr bool is_user_defined_function(std::uint8_t f) {
  return (f >= 0x41 && f <= 0x48) || (f >= 0x64 && f <= 0x6E);
}

namespace detail {

// What each function code is, as bits, so that the framing and the parser, which ask for
// every byte that may start a frame, look it up instead of walking switches.
enum FunctionKind : std::uint8_t { kHybridKind = 1, kGslKind = 2, kModbusKind = 4 };

constexpr bool is_public_code(unsigned f) {
  switch (f) {
    case kReadCoils:
    case kReadDiscreteInputs:
    case kGslReadHolding:
    case kGslReadInput:
    case kWriteSingleCoil:
    case kGslWriteSingle:
    case kReadExceptionStatus:
    case kDiagnostics:
    case kCommEventCounter:
    case kCommEventLog:
    case kWriteMultipleCoils:
    case kGslWriteMultiple:
    case kReportServerId:
    case kReadFileRecord:
    case kWriteFileRecord:
    case kMaskWriteRegister:
    case kReadWriteMultiple:
    case kReadFifoQueue:
    case kEncapsulatedInterface:
      return true;
    default:
      return false;
  }
}

constexpr std::uint8_t kind_of(unsigned f) {
  std::uint8_t k = 0;
  switch (f) {
    case kHybridDeviceInfo:
    case kHybridRunningData:
    case kHybridSettings:
    case kHybridManufacturer:
    case kHybridWriteParameter:
    case kHybridRestoreFactory:
    case kHybridError:
      k |= kHybridKind;
      break;
    default:
      break;
  }
  const unsigned base = f & ~unsigned{kExceptionFlag};
  const bool exception = (f & kExceptionFlag) != 0 && f != kHybridError;
  const bool gsl_code = base == kGslReadHolding || base == kGslReadInput ||
                        base == kGslWriteSingle || base == kGslWriteMultiple;
  if (gsl_code && f != kHybridError) k |= kGslKind;
  // Exceptions only to public or user-defined codes: half of all byte values would otherwise
  // start a 5-byte frame, and noise would turn into damaged frames.
  const bool user = (base >= 0x41 && base <= 0x48) || (base >= 0x64 && base <= 0x6E);
  if (is_public_code(f) || (exception && (is_public_code(base) || user))) k |= kModbusKind;
  return k;
}

struct FunctionKinds {
  std::uint8_t of[256];
};

constexpr FunctionKinds make_function_kinds() {
  FunctionKinds t{};
  for (unsigned f = 0; f < 256; ++f) t.of[f] = kind_of(f);
  return t;
}

inline constexpr FunctionKinds kFunctionKinds = make_function_kinds();

}  // namespace detail

constexpr bool is_hybrid_function(std::uint8_t f) {
  return (detail::kFunctionKinds.of[f] & detail::kHybridKind) != 0;
}

// The function codes of the GSL seed, and exceptions to them.
constexpr bool is_gsl_function(std::uint8_t f) {
  return (detail::kFunctionKinds.of[f] & detail::kGslKind) != 0;
}

// The public function codes with a length rule (section 6's table), without exceptions.
constexpr bool is_public_modbus_function(std::uint8_t f) {
  return detail::is_public_code(f);
}

// A function code the Modbus family frames by a length rule: the public codes, and the
// exception to a public or user-defined code (a device answers those it lacks with 01).
constexpr bool is_modbus_function(std::uint8_t f) {
  return (detail::kFunctionKinds.of[f] & detail::kModbusKind) != 0;
}

// The RTU dialect a function code names when nothing else is known: Hybrid for its codes
// (0x11 0x16 0x17 0x18 included: the station's history decides those,
// dialects/modbus/station_dialects.h), GSL for the seed's codes, plain Modbus for the other public
// codes; nullopt if none. (dialects/rtu_candidates.cpp, beside the rules that frame them.)
std::optional<Dialect> rtu_dialect_of(std::uint8_t f);

// A short human name for a function code of a dialect ("read running data").
std::string_view function_name(Dialect d, std::uint8_t f);

// The text of a Modbus exception code ("illegal data address"); GSL's own reading of the
// codes its seed uses where `d` is GSL.
std::string_view exception_name(std::uint8_t code);
std::string_view exception_name(Dialect d, std::uint8_t code);

// The name of a diagnostics (0x08) sub-function ("return query data"), or "" if unknown.
std::string_view diagnostics_name(std::uint16_t sub_function);

}  // namespace pvtap::fc
