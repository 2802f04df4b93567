#include "pvtap/codec/function_codes.h"

namespace pvtap::fc {

std::string_view function_name(Dialect d, std::uint8_t f) {
  if (d == Dialect::Ascii) return f == kAsciiRead ? "read" : "unknown";
  if (d == Dialect::Hybrid) {
    switch (f) {
      case kHybridDeviceInfo:
        return "device information";
      case kHybridRunningData:
        return "read running data";
      case kHybridSettings:
        return "read settings";
      case kHybridManufacturer:
        return "read manufacturer parameters";
      case kHybridWriteParameter:
        return "write parameter";
      case kHybridRestoreFactory:
        return "restore factory settings";
      case kHybridError:
        return "error reply";
      default:
        return "unknown";
    }
  }
  if (is_gsl_exception(f)) return "exception";
  switch (f) {
    case kGslReadHolding:
      return "read holding registers";
    case kGslReadInput:
      return "read input registers";
    case kGslWriteSingle:
      return "write single register";
    case kGslWriteMultiple:
      return "write multiple registers";
    default:
      return "unknown";
  }
}

std::string_view exception_name(std::uint8_t code) {
  switch (code) {
    case 0x01:
      return "unknown function code";
    case 0x02:
      return "address (ID) out of range";
    case 0x03:
      return "data not recognized (or CRC error)";
    case 0x06:
      return "device busy (data not ready)";
    default:
      return "undocumented exception code";
  }
}

}  // namespace pvtap::fc
