#include "dialects/modbus/modbus_codec.h"

#include "codec/wire_fields.h"

#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {
namespace {

constexpr std::size_t kHeader = 2;  // station, function
constexpr std::size_t kCrc = 2;

// The bytes between the function code and the CRC.
std::span<const std::uint8_t> body_of(std::span<const std::uint8_t> b) {
  return b.subspan(kHeader, b.size() - kHeader - kCrc);
}

// Body: n(1) and n bytes.
ParseStatus counted(std::span<const std::uint8_t> body, Frame& f, bool as_words) {
  if (body.empty() || body.size() != 1u + body[0]) {
    return fail("Modbus frame length disagrees with its byte count");
  }
  f.byte_count = body[0];
  const auto data = body.subspan(1);
  if (as_words) {
    if (!read_words(data, f.words)) return fail("Modbus register data is not whole registers");
  } else {
    f.data.assign(data);
  }
  return kParsed;
}

// Body: two 16-bit fields (address and value, or start and quantity).
ParseStatus two_fields(std::span<const std::uint8_t> body, Frame& f, bool second_is_count) {
  if (body.size() != 4) return fail("Modbus frame is not 8 bytes");
  f.start = be16(body, 0);
  if (second_is_count) {
    f.count = be16(body, 2);
  } else {
    f.words.push_back(be16(body, 2));
  }
  return kParsed;
}

ParseStatus empty_body(std::span<const std::uint8_t> body) {
  if (!body.empty()) return fail("Modbus request of this function carries no data");
  return kParsed;
}

ParseStatus diagnostics(std::span<const std::uint8_t> body, Frame& f) {
  if (body.size() < 2) return fail("Modbus diagnostics frame has no sub-function");
  f.sub_function = be16(body, 0);
  const auto data = body.subspan(2);
  if (data.size() % 2 == 0) {
    read_words(data, f.words);
  } else {
    f.data.assign(data);
  }
  return kParsed;
}

ParseStatus write_multiple_coils(std::span<const std::uint8_t> body, Frame& f) {
  if (body.size() < 5 || body.size() != 5u + body[4]) {
    return fail("Modbus 0x0F length disagrees with n");
  }
  f.start = be16(body, 0);
  f.count = be16(body, 2);
  f.byte_count = body[4];
  f.data.assign(body.subspan(5));
  return kParsed;
}

ParseStatus read_write_multiple(std::span<const std::uint8_t> body, Frame& f) {
  if (body.size() < 9 || body.size() != 9u + body[8]) {
    return fail("Modbus 0x17 length disagrees with n");
  }
  f.start = be16(body, 0);
  f.count = be16(body, 2);
  f.write_start = be16(body, 4);
  f.write_count = be16(body, 6);
  f.byte_count = body[8];
  if (!read_words(body.subspan(9), f.words)) return fail("Modbus 0x17 data is not whole registers");
  return kParsed;
}

ParseStatus mask_write(std::span<const std::uint8_t> body, Frame& f) {
  if (body.size() != 6) return fail("Modbus 0x16 frame is not 10 bytes");
  f.start = be16(body, 0);
  f.words.push_back(be16(body, 2));
  f.words.push_back(be16(body, 4));
  return kParsed;
}

ParseStatus fifo_reply(std::span<const std::uint8_t> body, Frame& f) {
  if (body.size() < 4) return fail("Modbus 0x18 reply shorter than its counts");
  const std::size_t n = be16(body, 0);
  if (body.size() != 2 + n || n > 0xFF)
    return fail("Modbus 0x18 length disagrees with its byte count");
  f.byte_count = static_cast<std::uint8_t>(n);
  f.count = be16(body, 2);
  if (!read_words(body.subspan(4), f.words)) return fail("Modbus 0x18 data is not whole registers");
  return kParsed;
}

ParseStatus raw(std::span<const std::uint8_t> body, Frame& f) {
  if (!f.data.assign(body)) return fail("Modbus frame longer than an ADU");
  return kParsed;
}

}  // namespace

ParseStatus parse_modbus_request(std::span<const std::uint8_t> b, Frame& f) {
  const auto body = body_of(b);
  switch (f.function) {
    case fc::kReadCoils:
    case fc::kReadDiscreteInputs:
      return two_fields(body, f, true);
    case fc::kWriteSingleCoil:
      return two_fields(body, f, false);
    case fc::kReadExceptionStatus:
    case fc::kCommEventCounter:
    case fc::kCommEventLog:
    case fc::kReportServerId:
      return empty_body(body);
    case fc::kDiagnostics:
      return diagnostics(body, f);
    case fc::kWriteMultipleCoils:
      return write_multiple_coils(body, f);
    case fc::kReadFileRecord:
    case fc::kWriteFileRecord:
      return counted(body, f, false);
    case fc::kMaskWriteRegister:
      return mask_write(body, f);
    case fc::kReadWriteMultiple:
      return read_write_multiple(body, f);
    case fc::kReadFifoQueue:
      if (body.size() != 2) return fail("Modbus 0x18 request is not 6 bytes");
      f.start = be16(body, 0);
      return kParsed;
    case fc::kEncapsulatedInterface:
      return raw(body, f);
    default:
      // A user-defined code has no public layout: its bytes are kept as they came.
      if (fc::is_user_defined_function(f.function)) return raw(body, f);
      return fail("not a Modbus request function code");
  }
}

ParseStatus parse_modbus_reply(std::span<const std::uint8_t> b, Frame& f) {
  const auto body = body_of(b);
  switch (f.function) {
    case fc::kReadCoils:
    case fc::kReadDiscreteInputs:
    case fc::kCommEventLog:
    case fc::kReportServerId:
    case fc::kReadFileRecord:
    case fc::kWriteFileRecord:
      return counted(body, f, false);
    case fc::kReadWriteMultiple:
      return counted(body, f, true);
    case fc::kWriteSingleCoil:
      return two_fields(body, f, false);
    case fc::kWriteMultipleCoils:
      return two_fields(body, f, true);
    case fc::kReadExceptionStatus:
      if (body.size() != 1) return fail("Modbus 0x07 reply is not 5 bytes");
      f.data.push_back(body[0]);
      return kParsed;
    case fc::kCommEventCounter:
      if (body.size() != 4) return fail("Modbus 0x0B reply is not 8 bytes");
      read_words(body, f.words);
      return kParsed;
    case fc::kDiagnostics:
      return diagnostics(body, f);
    case fc::kMaskWriteRegister:
      return mask_write(body, f);
    case fc::kReadFifoQueue:
      return fifo_reply(body, f);
    case fc::kEncapsulatedInterface:
      return raw(body, f);
    default:
      if (fc::is_user_defined_function(f.function)) return raw(body, f);
      return fail("not a Modbus reply function code");
  }
}

namespace {

bool put_counted_bytes(const Frame& f, std::vector<std::uint8_t>& out) {
  if (f.data.size() > 0xFF) return false;
  out.push_back(f.byte_count.value_or(static_cast<std::uint8_t>(f.data.size())));
  out.insert(out.end(), f.data.begin(), f.data.end());
  return true;
}

bool put_two_fields(const Frame& f, std::vector<std::uint8_t>& out, bool second_is_count) {
  if (!f.start) return false;
  put16(out, *f.start);
  if (second_is_count) {
    if (!f.count) return false;
    put16(out, *f.count);
  } else {
    if (f.words.size() != 1) return false;
    put16(out, f.words[0]);
  }
  return true;
}

bool encode_request_body(const Frame& f, std::vector<std::uint8_t>& out) {
  switch (f.function) {
    case fc::kReadCoils:
    case fc::kReadDiscreteInputs:
      return put_two_fields(f, out, true);
    case fc::kWriteSingleCoil:
      return put_two_fields(f, out, false);
    case fc::kReadExceptionStatus:
    case fc::kCommEventCounter:
    case fc::kCommEventLog:
    case fc::kReportServerId:
      return true;
    case fc::kWriteMultipleCoils:
      if (!put_two_fields(f, out, true)) return false;
      return put_counted_bytes(f, out);
    case fc::kReadFileRecord:
    case fc::kWriteFileRecord:
      return put_counted_bytes(f, out);
    case fc::kReadWriteMultiple:
      if (!f.start || !f.count || !f.write_start || !f.write_count) return false;
      if (f.words.size() * 2 > 0xFF) return false;
      put16(out, *f.start);
      put16(out, *f.count);
      put16(out, *f.write_start);
      put16(out, *f.write_count);
      out.push_back(f.byte_count.value_or(static_cast<std::uint8_t>(f.words.size() * 2)));
      for (auto w : f.words) put16(out, w);
      return true;
    case fc::kReadFifoQueue:
      if (!f.start) return false;
      put16(out, *f.start);
      return true;
    default:
      return false;
  }
}

bool encode_reply_body(const Frame& f, std::vector<std::uint8_t>& out) {
  switch (f.function) {
    case fc::kReadCoils:
    case fc::kReadDiscreteInputs:
    case fc::kCommEventLog:
    case fc::kReportServerId:
    case fc::kReadFileRecord:
    case fc::kWriteFileRecord:
      return put_counted_bytes(f, out);
    case fc::kReadWriteMultiple:
      if (f.words.size() * 2 > 0xFF) return false;
      out.push_back(f.byte_count.value_or(static_cast<std::uint8_t>(f.words.size() * 2)));
      for (auto w : f.words) put16(out, w);
      return true;
    case fc::kWriteSingleCoil:
      return put_two_fields(f, out, false);
    case fc::kWriteMultipleCoils:
      return put_two_fields(f, out, true);
    case fc::kReadExceptionStatus:
      if (f.data.size() != 1) return false;
      out.push_back(f.data[0]);
      return true;
    case fc::kCommEventCounter:
      if (f.words.size() != 2) return false;
      for (auto w : f.words) put16(out, w);
      return true;
    case fc::kReadFifoQueue: {
      if (!f.count || f.words.size() > 31) return false;
      put16(out, static_cast<std::uint16_t>(2 + 2 * f.words.size()));
      put16(out, *f.count);
      for (auto w : f.words) put16(out, w);
      return true;
    }
    default:
      return false;
  }
}

}  // namespace

bool encode_modbus_body(const Frame& f, std::vector<std::uint8_t>& out) {
  switch (f.function) {
    case fc::kDiagnostics:
      if (!f.sub_function) return false;
      put16(out, *f.sub_function);
      for (auto w : f.words) put16(out, w);
      out.insert(out.end(), f.data.begin(), f.data.end());
      return true;
    case fc::kMaskWriteRegister:
      if (!f.start || f.words.size() != 2) return false;
      put16(out, *f.start);
      put16(out, f.words[0]);
      put16(out, f.words[1]);
      return true;
    case fc::kEncapsulatedInterface:
      out.insert(out.end(), f.data.begin(), f.data.end());
      return true;
    default:
      if (fc::is_user_defined_function(f.function)) {
        out.insert(out.end(), f.data.begin(), f.data.end());
        return true;
      }
      return f.role == Role::Request ? encode_request_body(f, out) : encode_reply_body(f, out);
  }
}

}  // namespace pvtap::detail
