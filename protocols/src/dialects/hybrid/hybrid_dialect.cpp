// The Hybrid V2.2 dialect's record in the table of dialects (PROTOCOLS.md section 2).
#include "codec/rtu_codec.h"
#include "dialects/dialect_module.h"
#include "dialects/hybrid/hybrid_codec.h"
#include "pvtap/codec/function_codes.h"
#include "registers/register_value_conversion.h"
#include "registers/value_placement.h"

namespace pvtap::embedded {
extern const unsigned char map_hybrid[];
extern const std::size_t map_hybrid_size;
}  // namespace pvtap::embedded

namespace pvtap::detail {
namespace {

bool carries_hybrid(std::span<const std::uint8_t>, Role, std::uint8_t function) {
  return fc::is_hybrid_function(function);
}

bool writes_hybrid(std::uint8_t function) {
  return fc::is_hybrid_function(function);
}

ParseStatus parse_hybrid_body(std::span<const std::uint8_t> bytes, Role role, Frame& f) {
  return role == Role::Request ? parse_hybrid_request(bytes, f) : parse_hybrid_reply(bytes, f);
}

std::string_view hybrid_function_name(std::uint8_t f) {
  switch (f) {
    case fc::kHybridDeviceInfo:
      return "device information";
    case fc::kHybridRunningData:
      return "read running data";
    case fc::kHybridSettings:
      return "read settings";
    case fc::kHybridManufacturer:
      return "read manufacturer parameters";
    case fc::kHybridWriteParameter:
      return "write parameter";
    case fc::kHybridRestoreFactory:
      return "restore factory settings";
    case fc::kHybridError:
      return "error reply";
    default:
      return "unknown";
  }
}

// n = 4 + 2 x count for the reads, 8 for a write's echo and a restore's confirmation.
std::optional<CountComparison> compare_hybrid(const FrameSummary& request,
                                              const FrameSummary& reply) {
  if (!reply.byte_count) return std::nullopt;
  const unsigned found = *reply.byte_count;
  if (fc::is_hybrid_read(request.function)) {
    if (!request.count) return std::nullopt;
    return CountComparison{4u + 2u * unsigned{*request.count}, found, CountUnit::Bytes};
  }
  // The seed's table fixes n = 8 for both; 4 + 2*count would wrongly flag every 0x1F reply.
  if (request.function == fc::kHybridWriteParameter ||
      request.function == fc::kHybridRestoreFactory) {
    return CountComparison{8u, found, CountUnit::Bytes};
  }
  return std::nullopt;
}

// Function 0xFF answers any pending Hybrid request.
ReplyKind hybrid_reply_kind(std::uint8_t f) {
  return f == fc::kHybridError ? ReplyKind::HybridError : ReplyKind::Normal;
}

// The seed's default start of each Hybrid read, used when the request is missing.
std::optional<std::uint16_t> hybrid_default_start(std::uint8_t function) {
  switch (function) {
    case fc::kHybridDeviceInfo:
      return 0x1060;
    case fc::kHybridRunningData:
      return 0x1000;
    case fc::kHybridSettings:
      return 0x1024;
    case fc::kHybridManufacturer:
      return 0x104B;
    default:
      return std::nullopt;
  }
}

// A write's word at its start; a read reply's at its request's start, or the seed's default.
DecodeReport hybrid_values(const RegisterDecoder& decoder, const Frame& frame, const Frame* request,
                           std::vector<DecodedValue>& out) {
  const bool write = frame.function == fc::kHybridWriteParameter;
  if (frame.role == Role::Request) {
    if (!write || !frame.start || frame.words.empty()) return nothing(ValueOrigin::WriteRequest);
    return decoder.place(Dialect::Hybrid, *frame.start, first_word(frame),
                         ValueOrigin::WriteRequest, out);
  }
  if (write) {
    // A write echo of the wrong length keeps no register field: its words cannot be placed.
    if (!frame.start) return nothing(ValueOrigin::WriteReply, DecodeStatus::StartUnknown);
    return decoder.place(Dialect::Hybrid, *frame.start, first_word(frame), ValueOrigin::WriteReply,
                         out);
  }
  const std::optional<std::uint16_t> default_start = hybrid_default_start(frame.function);
  if (!default_start) return nothing(ValueOrigin::ReadReply);
  const bool usable = is_request_for(request, frame);
  const std::uint16_t start = usable ? *request->start : *default_start;
  DecodeReport report =
      decoder.place(Dialect::Hybrid, start, frame.words.span(), ValueOrigin::ReadReply, out);
  report.start_assumed = !usable;
  note_request_fit(report, frame, request);
  return report;
}

}  // namespace

extern const DialectModule kHybridDialect{
    .dialect = Dialect::Hybrid,
    .title = "Hybrid V2.2",
    .short_title = "Hybrid",
    .check_name = "CRC",
    .error_reply_name = "hybrid error reply (0xFF)",
    .rtu_framed = true,
    .parse =
        [](std::span<const std::uint8_t> bytes, Role role, Frame& out) {
          return parse_rtu<carries_hybrid, parse_hybrid_body>(bytes, Dialect::Hybrid, role, out);
        },
    .read_header = read_rtu_header,
    .verify_check = verify_rtu_check,
    .check_wire_bytes = rtu_check_wire_bytes,
    .encode = encode_rtu<writes_hybrid, encode_rtu_fields>,
    .function_name = hybrid_function_name,
    .exception_name = [](std::uint8_t code) { return fc::exception_name(code); },
    .builtin_map_text = []() -> std::string_view {
      return {reinterpret_cast<const char*>(embedded::map_hybrid), embedded::map_hybrid_size};
    },
    .reply_family = Dialect::Hybrid,
    .reply_kind = hybrid_reply_kind,
    // A gateway answers a Hybrid request it could not forward with a Modbus exception.
    .answered_by_gateway_exception = true,
    .reply_repeats_start = false,
    .reply_is_echo = [](std::uint8_t) { return false; },
    .compare_reply_count = compare_hybrid,
    .decimal_register_ids = false,
    .register_address_step = 1,
    .answered_broadcast_station = fc::kHybridBroadcast,
    .reply_may_be_modbus_family = true,
    .decode_values = hybrid_values,
};

}  // namespace pvtap::detail

namespace pvtap {

// The device number every Hybrid reply opens with, read by the Hybrid map's entry for it.
DecodedValue RegisterDecoder::decode_device_number(const DeviceNumber& device) const {
  const RegisterDef* def = map(Dialect::Hybrid).find_kind(RegisterKind::DeviceNumber);
  const std::array<std::uint16_t, 2> words{
      static_cast<std::uint16_t>((unsigned{device.type_code} << 8) |
                                 ((device.serial >> 16) & 0xFFu)),
      static_cast<std::uint16_t>(device.serial & 0xFFFFu)};
  DecodedValue v;
  v.def = def;
  v.origin = ValueOrigin::DeviceHeader;
  v.address = def != nullptr ? def->address : std::uint16_t{0};
  v.wire_address = v.address;
  v.words_present = 2;
  detail::convert_device_number(def, words, v);
  if (def == nullptr) v.add(ValueWarning::NotInMap);
  return v;
}

}  // namespace pvtap
