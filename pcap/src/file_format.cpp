#include "pvtap/pcap/file_format.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <memory>

namespace pvtap {
namespace {

bool starts_with(std::span<const std::uint8_t> bytes, std::initializer_list<std::uint8_t> magic) {
  return bytes.size() >= magic.size() && std::equal(magic.begin(), magic.end(), bytes.begin());
}

bool printable(std::uint8_t b) {
  return (b >= 0x20 && b < 0x7f) || b == '\n' || b == '\r' || b == '\t';
}

// The file's first bytes (fewer for a shorter file); empty when it cannot be read.
std::size_t read_start(const std::string& path, std::array<std::uint8_t, kFormatProbeBytes>& out) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), std::fclose);
  return f ? std::fread(out.data(), 1, out.size(), f.get()) : 0;
}

}  // namespace

FileFormat file_format_of(std::span<const std::uint8_t> b) {
  // pcap in either byte order, with micro- or nanosecond times; pcapng's section header.
  if (starts_with(b, {0xd4, 0xc3, 0xb2, 0xa1}) || starts_with(b, {0xa1, 0xb2, 0xc3, 0xd4}) ||
      starts_with(b, {0x4d, 0x3c, 0xb2, 0xa1}) || starts_with(b, {0xa1, 0xb2, 0x3c, 0x4d})) {
    return FileFormat::Pcap;
  }
  if (starts_with(b, {0x0a, 0x0d, 0x0d, 0x0a})) return FileFormat::Pcapng;
  if (starts_with(b, {'P', 'K', 0x03, 0x04})) return FileFormat::Zip;
  if (b.empty() || !std::all_of(b.begin(), b.end(), printable)) return FileFormat::Unknown;
  // A VCD opens with a $ keyword ($date, $timescale, $var ...), after white space at most.
  const auto first = std::find_if(b.begin(), b.end(), [](std::uint8_t c) {
    return c != ' ' && c != '\n' && c != '\r' && c != '\t';
  });
  return first != b.end() && *first == '$' ? FileFormat::Vcd : FileFormat::Text;
}

FileFormat file_format_of(const std::string& path) {
  std::array<std::uint8_t, kFormatProbeBytes> start{};
  const std::size_t n = read_start(path, start);
  if (n == 0) return FileFormat::Unreadable;
  return file_format_of(std::span(start).first(n));
}

std::string first_bytes_text(const std::string& path) {
  std::array<std::uint8_t, kFormatProbeBytes> start{};
  const std::size_t n = std::min<std::size_t>(read_start(path, start), 8);
  static const char kHex[] = "0123456789abcdef";
  std::string hex, text;
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0) hex += ' ';
    hex += kHex[start[i] >> 4];
    hex += kHex[start[i] & 0xf];
    text += start[i] >= 0x20 && start[i] < 0x7f ? static_cast<char>(start[i]) : '.';
  }
  return hex + " ('" + text + "')";
}

}  // namespace pvtap
