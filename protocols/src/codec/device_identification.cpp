#include "pvtap/codec/device_identification.h"

#include "pvtap/codec/function_codes.h"

namespace pvtap {
namespace {

constexpr std::size_t kObjectsAt = 6;  // MEI code conformity more next count

std::string_view text_of(std::span<const std::uint8_t> bytes) {
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

bool printable(std::uint8_t c) {
  return c >= 0x20 && c < 0x7F;
}

}  // namespace

std::string_view DeviceIdentification::object(std::uint8_t id) const {
  for (std::size_t i = 0; i < object_count; ++i) {
    if (objects[i].id == id) return objects[i].value;
  }
  return {};
}

std::optional<DeviceIdentification> read_device_identification(const Frame& reply) {
  const auto d = reply.data.span();
  if (reply.role != Role::Response || reply.function != fc::kEncapsulatedInterface ||
      d.size() < kObjectsAt || d[0] != fc::kMeiDeviceIdentification) {
    return std::nullopt;
  }
  DeviceIdentification out;
  out.read_code = d[1];
  out.conformity = d[2];
  out.more_follows = d[3] == 0xFF;
  out.next_object = d[4];
  const unsigned count = d[5];
  std::size_t at = kObjectsAt;
  for (unsigned i = 0; i < count; ++i) {
    if (at + 2 > d.size() || out.object_count == out.objects.size()) return std::nullopt;
    const std::size_t length = d[at + 1];
    if (at + 2 + length > d.size()) return std::nullopt;
    out.objects[out.object_count++] = {d[at], text_of(d.subspan(at + 2, length))};
    at += 2 + length;
  }
  return out;
}

std::string_view device_object_name(std::uint8_t id) {
  switch (id) {
    case 0x00:
      return "vendor name";
    case 0x01:
      return "product code";
    case 0x02:
      return "revision";
    case 0x03:
      return "vendor URL";
    case 0x04:
      return "product name";
    case 0x05:
      return "model name";
    case 0x06:
      return "user application name";
    default:
      return id >= 0x80 ? "private object" : "reserved object";
  }
}

std::optional<ServerId> read_server_id(const Frame& reply) {
  if (reply.role != Role::Response || reply.function != fc::kReportServerId || reply.data.empty()) {
    return std::nullopt;
  }
  const auto d = reply.data.span();
  ServerId out;
  if (d.size() > 1 && (d[1] == 0x00 || d[1] == 0xFF)) out.running = d[1] == 0xFF;
  std::size_t best_at = 0, best_length = 0;
  for (std::size_t i = 0; i < d.size();) {
    std::size_t j = i;
    while (j < d.size() && printable(d[j])) ++j;
    if (j - i > best_length) {
      best_at = i;
      best_length = j - i;
    }
    i = j == i ? i + 1 : j;
  }
  // A short run is as likely an ID byte that happens to be printable as a name.
  if (best_length >= 3) out.text = text_of(d.subspan(best_at, best_length));
  return out;
}

}  // namespace pvtap
