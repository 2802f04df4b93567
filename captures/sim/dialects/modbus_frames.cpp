#include "dialects/modbus_frames.h"

#include <bit>

#include "pvtap/codec/function_codes.h"

namespace pvtap::sim {
namespace {

Frame reply_to(const Frame& request, std::uint8_t function) {
  return make_frame(Dialect::Modbus, Role::Response, request.station, function);
}

// Bit 0 of byte 0 is the first state.
ByteList packed(const std::vector<bool>& states) {
  ByteList bytes;
  for (std::size_t i = 0; i < states.size(); i += 8) {
    std::uint8_t b = 0;
    for (std::size_t j = 0; j < 8 && i + j < states.size(); ++j)
      if (states[i + j]) b = static_cast<std::uint8_t>(b | 1u << j);
    bytes.push_back(b);
  }
  return bytes;
}

void push_object(ByteList& data, std::uint8_t id, std::string_view text) {
  data.push_back(id);
  data.push_back(static_cast<std::uint8_t>(text.size()));
  for (char c : text) data.push_back(static_cast<std::uint8_t>(c));
}

}  // namespace

Frame modbus_request(std::uint8_t station, std::uint8_t function) {
  return make_frame(Dialect::Modbus, Role::Request, station, function);
}

Frame write_multiple_registers(std::uint8_t station, std::uint16_t start, const WordList& words) {
  Frame f = modbus_request(station, fc::kGslWriteMultiple);
  f.start = start;
  f.count = static_cast<std::uint16_t>(words.size());
  f.byte_count = static_cast<std::uint8_t>(2 * words.size());
  f.words = words;
  return f;
}

Frame modbus_read(std::uint8_t station, std::uint8_t function, std::uint16_t start,
                  std::uint16_t count) {
  Frame f = modbus_request(station, function);
  f.start = start;
  f.count = count;
  return f;
}

Frame write_single_coil(std::uint8_t station, std::uint16_t coil, bool on) {
  Frame f = modbus_request(station, fc::kWriteSingleCoil);
  f.start = coil;
  f.words.push_back(on ? 0xFF00 : 0x0000);
  return f;
}

Frame write_single_register(std::uint8_t station, std::uint16_t address, std::uint16_t value) {
  Frame f = modbus_request(station, fc::kGslWriteSingle);
  f.start = address;
  f.words.push_back(value);
  return f;
}

Frame write_multiple_coils(std::uint8_t station, std::uint16_t start,
                           const std::vector<bool>& states) {
  Frame f = modbus_request(station, fc::kWriteMultipleCoils);
  f.start = start;
  f.count = static_cast<std::uint16_t>(states.size());
  f.data = packed(states);
  f.byte_count = static_cast<std::uint8_t>(f.data.size());
  return f;
}

Frame return_query_data(std::uint8_t station, std::uint16_t data) {
  Frame f = modbus_request(station, fc::kDiagnostics);
  f.sub_function = 0x0000;
  f.words.push_back(data);
  return f;
}

Frame read_device_identification(std::uint8_t station) {
  Frame f = modbus_request(station, fc::kEncapsulatedInterface);
  f.data = ByteList{fc::kMeiDeviceIdentification, 0x01, 0x00};
  return f;
}

Frame report_server_id(std::uint8_t station) {
  return modbus_request(station, fc::kReportServerId);
}

Frame echo_of(const Frame& request) {
  Frame f = request;
  f.role = Role::Response;
  return f;
}

Frame register_reply(const Frame& request, const WordList& words) {
  Frame f = reply_to(request, request.function);
  f.words = words;
  f.byte_count = static_cast<std::uint8_t>(2 * words.size());
  return f;
}

Frame bits_reply(const Frame& request, const std::vector<bool>& bits) {
  Frame f = reply_to(request, request.function);
  f.data = packed(bits);
  f.byte_count = static_cast<std::uint8_t>(f.data.size());
  return f;
}

Frame write_multiple_reply(const Frame& request) {
  Frame f = reply_to(request, request.function);
  f.start = request.start;
  f.count = request.count;
  return f;
}

Frame exception_reply(const Frame& request, std::uint8_t code) {
  Frame f = reply_to(request, static_cast<std::uint8_t>(request.function | fc::kExceptionFlag));
  f.exception_code = code;
  return f;
}

Frame device_identification_reply(const Frame& request, std::string_view vendor,
                                  std::string_view product, std::string_view revision) {
  Frame f = reply_to(request, fc::kEncapsulatedInterface);
  // MEI type, read code, conformity level, more follows, next object id, number of objects.
  f.data = ByteList{fc::kMeiDeviceIdentification, 0x01, 0x01, 0x00, 0x00, 0x03};
  push_object(f.data, 0x00, vendor);
  push_object(f.data, 0x01, product);
  push_object(f.data, 0x02, revision);
  return f;
}

Frame server_id_reply(const Frame& request, std::uint8_t server_id, std::string_view text) {
  Frame f = reply_to(request, fc::kReportServerId);
  f.data = ByteList{server_id, 0xFF};
  for (char c : text) f.data.push_back(static_cast<std::uint8_t>(c));
  f.byte_count = static_cast<std::uint8_t>(f.data.size());
  return f;
}

std::uint32_t float_bits(float value) {
  return std::bit_cast<std::uint32_t>(value);
}

void push_float(WordList& words, float value, bool low_first) {
  const std::uint32_t bits = float_bits(value);
  const auto high = static_cast<std::uint16_t>(bits >> 16);
  const auto low = static_cast<std::uint16_t>(bits & 0xFFFF);
  words.push_back(low_first ? low : high);
  words.push_back(low_first ? high : low);
}

std::uint16_t text_word(std::string_view text, unsigned index) {
  const auto c = [&](unsigned i) -> unsigned {
    return i < text.size() ? static_cast<unsigned char>(text[i]) : 0u;
  };
  return static_cast<std::uint16_t>(c(2 * index) << 8 | c(2 * index + 1));
}

WordList register_words(const Frame& request,
                        const std::function<std::uint16_t(std::uint16_t)>& word_at) {
  WordList words;
  const std::uint16_t start = request.start.value_or(0), count = request.count.value_or(0);
  for (unsigned a = start; a < start + count; ++a)
    words.push_back(word_at(static_cast<std::uint16_t>(a)));
  return words;
}

}  // namespace pvtap::sim
