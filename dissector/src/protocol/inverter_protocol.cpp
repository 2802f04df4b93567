#include "protocol/inverter_protocol.h"

namespace pvtap::dissector {
namespace {

InverterProtocol g_rtu{
    .name = "Inverter RTU protocol",
    .short_name = "invRTU",
    .filter_name = "invrtu",
    .check_name = "CRC",
    .check_key = "crc",
    .check_word = "CRC",
    .dialects = DialectSet::none().with(Dialect::Hybrid).with(Dialect::Gsl).with(Dialect::Modbus),
};

InverterProtocol g_ascii{
    .name = "Inverter ASCII protocol",
    .short_name = "invASCII",
    .filter_name = "invascii",
    .check_name = "Checksum",
    .check_key = "checksum",
    .check_word = "checksum",
    .dialects = DialectSet::only(Dialect::Ascii),
};

}  // namespace

InverterProtocol& rtu_protocol() {
  return g_rtu;
}

InverterProtocol& ascii_protocol() {
  return g_ascii;
}

InverterProtocol& protocol_of(Dialect d) {
  return d == Dialect::Ascii ? g_ascii : g_rtu;
}

}  // namespace pvtap::dissector
