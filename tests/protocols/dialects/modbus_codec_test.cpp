// The public Modbus function codes: the worked examples of the Modbus Application Protocol
// Specification V1.1b3 (PDUs, here sent to station 0x11), parsed and encoded again.
#include <gtest/gtest.h>

#include <string>

#include "hex_bytes.h"
#include "pvtap/codec/checksums.h"
#include "pvtap/codec/device_identification.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap {
namespace {

using test::hex_bytes;

// Station 0x11, the PDU, and its CRC: the serial line ADU of a specification example.
std::vector<std::uint8_t> adu(std::string_view pdu) {
  std::vector<std::uint8_t> out = hex_bytes("11");
  const auto body = hex_bytes(pdu);
  out.insert(out.end(), body.begin(), body.end());
  const std::uint16_t crc = Crc16Modbus::compute(out);
  out.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  out.push_back(static_cast<std::uint8_t>(crc >> 8));
  return out;
}

Frame parsed(std::string_view pdu, Role role) {
  const auto bytes = adu(pdu);
  const ParseOutcome p = parse_frame(bytes, Dialect::Modbus, role);
  EXPECT_TRUE(p) << pdu << ": " << (p ? "" : p.error_text());
  if (!p) return {};
  EXPECT_EQ(encode_frame(p.value()), bytes) << "round trip of " << pdu;
  EXPECT_TRUE(verify_check(bytes, Dialect::Modbus).ok);
  return p.value();
}

TEST(ModbusCodec, TheSerialLineGuidesReadCoilsFrameHasAGoodCrc) {
  const auto frame = hex_bytes("11 01 00 13 00 25 0E 84");
  EXPECT_TRUE(verify_check(frame, Dialect::Modbus).ok);
  EXPECT_EQ(adu("01 00 13 00 25"), frame);
}

TEST(ModbusCodec, ReadCoilsRequestAndReply) {
  const Frame q = parsed("01 00 13 00 13", Role::Request);
  EXPECT_EQ(q.start, 0x13);
  EXPECT_EQ(q.count, 19);
  const Frame r = parsed("01 03 CD 6B 05", Role::Response);
  EXPECT_EQ(r.byte_count, 3);
  EXPECT_EQ(r.data, (ByteList{0xCD, 0x6B, 0x05}));
}

TEST(ModbusCodec, ReadDiscreteInputsReply) {
  EXPECT_EQ(parsed("02 00 C4 00 16", Role::Request).count, 22);
  EXPECT_EQ(parsed("02 03 AC DB 35", Role::Response).data, (ByteList{0xAC, 0xDB, 0x35}));
}

TEST(ModbusCodec, RegisterReadsAreTheGslForms) {
  const Frame r = parsed("03 06 02 2B 00 00 00 64", Role::Response);
  EXPECT_EQ(r.words, (WordList{0x022B, 0x0000, 0x0064}));
  EXPECT_EQ(parsed("04 02 00 0A", Role::Response).words, (WordList{0x000A}));
}

TEST(ModbusCodec, SingleWritesAreEchoed) {
  const Frame coil = parsed("05 00 AC FF 00", Role::Request);
  EXPECT_EQ(coil.start, 0x00AC);
  EXPECT_EQ(coil.words, (WordList{0xFF00}));
  Frame echo = coil;
  echo.role = Role::Response;
  EXPECT_EQ(parsed("05 00 AC FF 00", Role::Response), echo);
  EXPECT_EQ(parsed("06 00 01 00 03", Role::Request).words, (WordList{0x0003}));
}

TEST(ModbusCodec, ExceptionStatusDiagnosticsAndEventCounter) {
  EXPECT_TRUE(parsed("07", Role::Request).data.empty());
  EXPECT_EQ(parsed("07 6D", Role::Response).data, (ByteList{0x6D}));
  const Frame diag = parsed("08 00 00 A5 37", Role::Request);
  EXPECT_EQ(diag.sub_function, 0x0000);
  EXPECT_EQ(diag.words, (WordList{0xA537}));
  EXPECT_EQ(fc::diagnostics_name(*diag.sub_function), "return query data");
  EXPECT_EQ(parsed("0B FF FF 01 08", Role::Response).words, (WordList{0xFFFF, 0x0108}));
}

TEST(ModbusCodec, MultipleWrites) {
  const Frame coils = parsed("0F 00 13 00 0A 02 CD 01", Role::Request);
  EXPECT_EQ(coils.start, 0x13);
  EXPECT_EQ(coils.count, 10);
  EXPECT_EQ(coils.data, (ByteList{0xCD, 0x01}));
  EXPECT_EQ(parsed("0F 00 13 00 0A", Role::Response).count, 10);
  EXPECT_EQ(parsed("10 00 01 00 02 04 00 0A 01 02", Role::Request).words,
            (WordList{0x000A, 0x0102}));
  EXPECT_EQ(parsed("10 00 01 00 02", Role::Response).count, 2);
}

TEST(ModbusCodec, MaskWriteReadWriteAndFifo) {
  EXPECT_EQ(parsed("16 00 04 00 F2 00 25", Role::Request).words, (WordList{0x00F2, 0x0025}));
  const Frame rw = parsed("17 00 03 00 06 00 0E 00 03 06 00 FF 00 FF 00 FF", Role::Request);
  EXPECT_EQ(rw.start, 3);
  EXPECT_EQ(rw.count, 6);
  EXPECT_EQ(rw.write_start, 0x0E);
  EXPECT_EQ(rw.write_count, 3);
  EXPECT_EQ(rw.words.size(), 3u);
  EXPECT_EQ(parsed("17 0C 00 FE 0A CD 00 01 00 03 00 0D 00 FF", Role::Response).words.size(), 6u);
  EXPECT_EQ(parsed("18 04 DE", Role::Request).start, 0x04DE);
  const Frame fifo = parsed("18 00 06 00 02 01 B8 12 84", Role::Response);
  EXPECT_EQ(fifo.count, 2);
  EXPECT_EQ(fifo.words, (WordList{0x01B8, 0x1284}));
}

TEST(ModbusCodec, FileRecordsAndServerIdAreRawData) {
  EXPECT_EQ(parsed("14 0E 06 00 04 00 01 00 02 06 00 03 00 09 00 02", Role::Request).data.size(),
            14u);
  EXPECT_EQ(parsed("11", Role::Request).function, fc::kReportServerId);
  const Frame id = parsed("11 07 2A FF 50 56 54 41 50", Role::Response);
  const auto server = read_server_id(id);
  ASSERT_TRUE(server);
  EXPECT_EQ(server->running, true);
  EXPECT_EQ(server->text, "PVTAP");
}

TEST(ModbusCodec, DeviceIdentificationNamesTheDevice) {
  EXPECT_EQ(parsed("2B 0E 01 00", Role::Request).data, (ByteList{0x0E, 0x01, 0x00}));
  // The example's objects: "Company identification", "Product code XX", "V2.11".
  const auto text_hex = [](std::string_view s) {
    static const char* d = "0123456789ABCDEF";
    std::string out;
    for (const char ch : s) {
      const auto c = static_cast<unsigned char>(ch);
      out += ' ';
      out += d[c >> 4];
      out += d[c & 0xF];
    }
    return out;
  };
  const std::string pdu = "2B 0E 01 01 00 00 03 00 16" + text_hex("Company identification") +
                          " 01 0F" + text_hex("Product code XX") + " 02 05" + text_hex("V2.11");
  const Frame r = parsed(pdu, Role::Response);
  const auto id = read_device_identification(r);
  ASSERT_TRUE(id);
  EXPECT_EQ(id->conformity, 0x01);
  EXPECT_EQ(id->vendor(), "Company identification");
  EXPECT_EQ(id->product(), "Product code XX");
  EXPECT_EQ(id->revision(), "V2.11");
  EXPECT_EQ(device_object_name(0x02), "revision");
}

TEST(ModbusCodec, DeviceIdentificationThatOverrunsItsFrameIsNotRead) {
  const Frame r = parsed("2B 0E 01 01 00 00 02 00 03 41 42 43 01 09 41", Role::Response);
  EXPECT_FALSE(read_device_identification(r));
}

TEST(ModbusCodec, ExceptionsHaveTheNineNames) {
  const Frame e = parsed("81 02", Role::Response);
  EXPECT_EQ(e.exception_code, 2);
  EXPECT_EQ(fc::exception_name(Dialect::Modbus, 0x02), "illegal data address");
  EXPECT_EQ(fc::exception_name(Dialect::Modbus, 0x0B), "gateway target device failed to respond");
  // GSL keeps its seed's reading of the codes it uses.
  EXPECT_EQ(fc::exception_name(Dialect::Gsl, 0x02), "address (ID) out of range");
}

TEST(ModbusCodec, GslDoesNotTakeTheOtherCodes) {
  const ParseOutcome p = parse_frame(adu("01 00 13 00 13"), Dialect::Gsl, Role::Request);
  EXPECT_FALSE(p);
  EXPECT_TRUE(parse_frame(adu("03 00 6B 00 03"), Dialect::Gsl, Role::Request));
}

TEST(ModbusCodec, AByteCountThatLiesDoesNotParse) {
  EXPECT_FALSE(parse_frame(adu("01 03 CD 6B"), Dialect::Modbus, Role::Response));
  EXPECT_FALSE(parse_frame(adu("0F 00 13 00 0A 03 CD 01"), Dialect::Modbus, Role::Request));
}

}  // namespace
}  // namespace pvtap
