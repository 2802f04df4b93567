#include "protocol/inverter_protocol.h"

namespace pvtap::dissector {
namespace {

// The dialects whose frames are RTU frames, or those whose are not.
DialectSet framed_so(bool rtu) {
  DialectSet set = DialectSet::none();
  for (const Dialect d : kAllDialects) {
    if (rtu_framed(d) == rtu) set = set.with(d);
  }
  return set;
}

InverterProtocol g_rtu{
    .name = "Inverter RTU protocol",
    .short_name = "invRTU",
    .filter_name = "invrtu",
    .check_name = "CRC",
    .check_key = "crc",
    .check_word = "CRC",
    .dialects = framed_so(true),
};

InverterProtocol g_ascii{
    .name = "Inverter ASCII protocol",
    .short_name = "invASCII",
    .filter_name = "invascii",
    .check_name = "Checksum",
    .check_key = "checksum",
    .check_word = "checksum",
    .dialects = framed_so(false),
};

}  // namespace

InverterProtocol& rtu_protocol() {
  return g_rtu;
}

InverterProtocol& ascii_protocol() {
  return g_ascii;
}

InverterProtocol& protocol_of(Dialect d) {
  return rtu_framed(d) ? g_rtu : g_ascii;
}

}  // namespace pvtap::dissector
