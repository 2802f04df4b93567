#include "pvtap/codec/function_codes.h"

#include "dialects/dialect_module.h"

namespace pvtap::fc {
std::string_view function_name(Dialect d, std::uint8_t f) {
  return pvtap::detail::dialect_module(d).function_name(f);
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
  return pvtap::detail::dialect_module(d).exception_name(code);
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
