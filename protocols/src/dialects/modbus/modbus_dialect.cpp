// The GSL and plain Modbus dialects' records in the table of dialects (PROTOCOLS.md sections
// 3 and 6): one wire, two readings of its registers (GSL is Modbus RTU with KSTAR's map).
#include "codec/rtu_codec.h"
#include "dialects/dialect_module.h"
#include "dialects/modbus/gsl_codec.h"
#include "dialects/modbus/modbus_codec.h"
#include "pvtap/codec/function_codes.h"
#include "registers/value_placement.h"

namespace pvtap::embedded {
extern const unsigned char map_gsl[];
extern const std::size_t map_gsl_size;
}  // namespace pvtap::embedded

namespace pvtap::fc {
namespace {

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

// GSL and Modbus name a code alike: the seed's names for GSL's codes, the specification's
// for the others.
std::string_view modbus_family_function_name(std::uint8_t f) {
  if (is_gsl_exception(f)) return "exception";
  const std::string_view gsl = gsl_function_name(f);
  if (!gsl.empty()) return gsl;
  return modbus_function_name(f);
}

// The Modbus Application Protocol's names of the exception codes.
std::string_view modbus_exception_name(std::uint8_t code) {
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

}  // namespace
}  // namespace pvtap::fc

namespace pvtap::detail {
namespace {

// A gateway's own exception (0x0A, 0x0B) answers whatever it forwarded, a function of another
// dialect included (a Hybrid read through a Modbus/TCP gateway): station, fc|0x80, code, CRC.
bool gateway_exception(std::span<const std::uint8_t> b, Role role) {
  return role == Role::Response && b.size() == 5 && fc::is_gsl_exception(b[1]) &&
         (b[2] == fc::kGatewayPathUnavailable || b[2] == fc::kGatewayTargetNoResponse);
}

bool carries_gsl(std::span<const std::uint8_t> b, Role role, std::uint8_t function) {
  return fc::is_gsl_function(function) || gateway_exception(b, role);
}

bool writes_gsl(std::uint8_t function) {
  return fc::is_gsl_function(function);
}

// A user-defined code of plain Modbus (PROTOCOLS.md section 6) has no public layout, so its
// bytes are kept as they came; the framing finds such a frame only between pinned ends.
bool carries_modbus(std::span<const std::uint8_t> b, Role role, std::uint8_t function) {
  return fc::is_modbus_function(function) || gateway_exception(b, role) ||
         fc::is_user_defined_function(function);
}

bool writes_modbus(std::uint8_t function) {
  return fc::is_modbus_function(function) || fc::is_user_defined_function(function);
}

// GSL's codes by GSL's rules, which plain Modbus shares; the other public codes by Modbus's.
ParseStatus parse_modbus_family_body(std::span<const std::uint8_t> b, Role role, Frame& f) {
  if (fc::is_gsl_function(f.function)) {
    return role == Role::Request ? parse_gsl_request(b, f) : parse_gsl_reply(b, f);
  }
  if (fc::is_gsl_exception(f.function)) {
    if (role == Role::Request) return fail("an exception is never a request");
    return parse_gsl_reply(b, f);
  }
  return role == Role::Request ? parse_modbus_request(b, f) : parse_modbus_reply(b, f);
}

bool encode_modbus_family_body(const Frame& f, std::vector<std::uint8_t>& out) {
  const bool plain_modbus = !fc::is_gsl_function(f.function) && !fc::is_gsl_exception(f.function);
  return plain_modbus ? encode_modbus_body(f, out) : encode_rtu_fields(f, out);
}

// GSL and plain Modbus: the reads whose reply carries a byte count the request fixes.
std::optional<CountComparison> compare_modbus(const FrameSummary& request,
                                              const FrameSummary& reply) {
  if (!request.count || !reply.byte_count) return std::nullopt;
  const unsigned qty = *request.count;
  const unsigned found = *reply.byte_count;
  switch (request.function) {
    case fc::kGslReadHolding:
    case fc::kGslReadInput:
    case fc::kReadWriteMultiple:
      return CountComparison{2u * qty, found, CountUnit::Bytes};
    case fc::kReadCoils:
    case fc::kReadDiscreteInputs:
      return CountComparison{(qty + 7u) / 8u, found, CountUnit::Bytes};
    default:
      return std::nullopt;
  }
}

// The functions whose normal reply repeats the request unchanged.
bool is_echoed(std::uint8_t f) {
  return f == fc::kGslWriteSingle || f == fc::kWriteSingleCoil || f == fc::kDiagnostics ||
         f == fc::kMaskWriteRegister || f == fc::kWriteFileRecord;
}

// GSL and plain Modbus: register reads and writes; other functions carry no register values.
DecodeReport modbus_family_values(const RegisterDecoder& decoder, const Frame& frame,
                                  const Frame* request, std::vector<DecodedValue>& out) {
  decoder.learn(frame, request);
  const RegisterMap* own = decoder.station_map(frame.station);
  const RegisterMap& m = own != nullptr ? *own : decoder.map(frame.dialect);
  const Dialect d = own != nullptr ? own->dialect() : frame.dialect;
  if (frame.role == Role::Request) {
    if (!frame.start || frame.words.empty()) return nothing(ValueOrigin::WriteRequest);
    if (frame.function == fc::kGslWriteSingle) {
      return decoder.place(m, d, *frame.start, first_word(frame), ValueOrigin::WriteRequest, out);
    }
    if (frame.function == fc::kGslWriteMultiple ||
        (frame.function == fc::kReadWriteMultiple && frame.write_start)) {
      const std::uint16_t at =
          frame.function == fc::kReadWriteMultiple ? *frame.write_start : *frame.start;
      return decoder.place(m, d, at, frame.words.span(), ValueOrigin::WriteRequest, out);
    }
    return nothing(ValueOrigin::WriteRequest);
  }
  if (frame.function == fc::kGslWriteSingle && frame.start && !frame.words.empty()) {
    return decoder.place(m, d, *frame.start, first_word(frame), ValueOrigin::WriteReply, out);
  }
  const bool read = frame.function == fc::kGslReadHolding || frame.function == fc::kGslReadInput ||
                    frame.function == fc::kReadWriteMultiple;
  if (!read) return nothing(ValueOrigin::ReadReply);
  if (!is_request_for(request, frame)) {
    DecodeReport report = nothing(ValueOrigin::ReadReply, DecodeStatus::StartUnknown);
    report.request_unusable = request != nullptr;
    return report;
  }
  DecodeReport report =
      decoder.place(m, d, *request->start, frame.words.span(), ValueOrigin::ReadReply, out);
  note_request_fit(report, frame, request);
  decoder.apply_scale_factors(m, frame.station, report, out);
  return report;
}

// fc|0x80 answers fc.
ReplyKind modbus_reply_kind(std::uint8_t f) {
  return fc::is_gsl_exception(f) ? ReplyKind::GslException : ReplyKind::Normal;
}

}  // namespace

extern const DialectModule kGslDialect{
    .dialect = Dialect::Gsl,
    .title = "GSL (Modbus RTU)",
    .short_title = "GSL",
    .check_name = "CRC",
    .error_reply_name = "",
    .rtu_framed = true,
    .parse =
        [](std::span<const std::uint8_t> bytes, Role role, Frame& out) {
          return parse_rtu<carries_gsl, parse_modbus_family_body>(bytes, Dialect::Gsl, role, out);
        },
    .read_header = read_rtu_header,
    .verify_check = verify_rtu_check,
    .check_wire_bytes = rtu_check_wire_bytes,
    .encode = encode_rtu<writes_gsl, encode_modbus_family_body>,
    .function_name = fc::modbus_family_function_name,
    .exception_name = [](std::uint8_t code) { return fc::exception_name(code); },
    .builtin_map_text = []() -> std::string_view {
      return {reinterpret_cast<const char*>(embedded::map_gsl), embedded::map_gsl_size};
    },
    .reply_family = Dialect::Gsl,
    .reply_kind = modbus_reply_kind,
    .answered_by_gateway_exception = false,
    .reply_repeats_start = false,
    .reply_is_echo = is_echoed,
    .compare_reply_count = compare_modbus,
    .decimal_register_ids = true,
    .register_address_step = 1,
    .answered_broadcast_station = -1,
    .reply_may_be_modbus_family = false,
    .decode_values = modbus_family_values,
};

// Plain Modbus devices bring their own map (--map STATION=FILE).
extern const DialectModule kModbusDialect{
    .dialect = Dialect::Modbus,
    .title = "Modbus RTU",
    .short_title = "plain Modbus",
    .check_name = "CRC",
    .error_reply_name = "",
    .rtu_framed = true,
    .parse =
        [](std::span<const std::uint8_t> bytes, Role role, Frame& out) {
          return parse_rtu<carries_modbus, parse_modbus_family_body>(bytes, Dialect::Modbus, role,
                                                                     out);
        },
    .read_header = read_rtu_header,
    .verify_check = verify_rtu_check,
    .check_wire_bytes = rtu_check_wire_bytes,
    .encode = encode_rtu<writes_modbus, encode_modbus_family_body>,
    .function_name = fc::modbus_family_function_name,
    .exception_name = fc::modbus_exception_name,
    .builtin_map_text = []() -> std::string_view { return {}; },
    .reply_family = Dialect::Gsl,
    .reply_kind = modbus_reply_kind,
    .answered_by_gateway_exception = false,
    .reply_repeats_start = false,
    .reply_is_echo = is_echoed,
    .compare_reply_count = compare_modbus,
    .decimal_register_ids = false,
    .register_address_step = 1,
    .answered_broadcast_station = -1,
    .reply_may_be_modbus_family = false,
    .decode_values = modbus_family_values,
};

}  // namespace pvtap::detail
