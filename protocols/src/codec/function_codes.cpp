#include "pvtap/codec/function_codes.h"

namespace pvtap::fc {
namespace {

std::string_view hybrid_function_name(std::uint8_t f) {
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

// The seed's names for the GSL codes (kept: reports and the plugin have always shown them).
std::string_view gsl_function_name(std::uint8_t f) {
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
      return {};
  }
}

std::string_view modbus_function_name(std::uint8_t f) {
  switch (f) {
    case kReadCoils:
      return "read coils";
    case kReadDiscreteInputs:
      return "read discrete inputs";
    case kWriteSingleCoil:
      return "write single coil";
    case kReadExceptionStatus:
      return "read exception status";
    case kDiagnostics:
      return "diagnostics";
    case kCommEventCounter:
      return "get comm event counter";
    case kCommEventLog:
      return "get comm event log";
    case kWriteMultipleCoils:
      return "write multiple coils";
    case kReportServerId:
      return "report server ID";
    case kReadFileRecord:
      return "read file record";
    case kWriteFileRecord:
      return "write file record";
    case kMaskWriteRegister:
      return "mask write register";
    case kReadWriteMultiple:
      return "read/write multiple registers";
    case kReadFifoQueue:
      return "read FIFO queue";
    case kEncapsulatedInterface:
      return "encapsulated interface (device identification)";
    default:
      break;
  }
  if (is_user_defined_function(f)) return "user-defined function";
  return "unknown";
}

}  // namespace

std::string_view function_name(Dialect d, std::uint8_t f) {
  if (d == Dialect::Ascii) return f == kAsciiRead ? "read" : "unknown";
  if (d == Dialect::Hybrid) return hybrid_function_name(f);
  if (is_gsl_exception(f)) return "exception";
  const std::string_view gsl = gsl_function_name(f);
  if (!gsl.empty()) return gsl;
  return modbus_function_name(f);
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

std::string_view exception_name(Dialect d, std::uint8_t code) {
  if (d != Dialect::Modbus) return exception_name(code);
  switch (code) {
    case 0x01:
      return "illegal function";
    case 0x02:
      return "illegal data address";
    case 0x03:
      return "illegal data value";
    case 0x04:
      return "server device failure";
    case 0x05:
      return "acknowledge";
    case 0x06:
      return "server device busy";
    case 0x08:
      return "memory parity error";
    case 0x0A:
      return "gateway path unavailable";
    case 0x0B:
      return "gateway target device failed to respond";
    default:
      return "undocumented exception code";
  }
}

std::string_view diagnostics_name(std::uint16_t sub_function) {
  switch (sub_function) {
    case 0x00:
      return "return query data";
    case 0x01:
      return "restart communications option";
    case 0x02:
      return "return diagnostic register";
    case 0x03:
      return "change ASCII input delimiter";
    case 0x04:
      return "force listen only mode";
    case 0x0A:
      return "clear counters and diagnostic register";
    case 0x0B:
      return "return bus message count";
    case 0x0C:
      return "return bus communication error count";
    case 0x0D:
      return "return bus exception error count";
    case 0x0E:
      return "return server message count";
    case 0x0F:
      return "return server no response count";
    case 0x10:
      return "return server NAK count";
    case 0x11:
      return "return server busy count";
    case 0x12:
      return "return bus character overrun count";
    case 0x14:
      return "clear overrun counter and flag";
    default:
      return {};
  }
}

}  // namespace pvtap::fc
