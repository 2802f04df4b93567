#include "formatting/number_text.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <ctime>

namespace pvtap::analyzer {
namespace {

constexpr char kHexDigits[] = "0123456789abcdef";

// "00" .. "99": numbers are written two digits per division.
constexpr auto kDigitPairs = [] {
  std::array<char, 200> pairs{};
  for (std::size_t i = 0; i < 100; ++i) {
    pairs[2 * i] = static_cast<char>('0' + i / 10);
    pairs[2 * i + 1] = static_cast<char>('0' + i % 10);
  }
  return pairs;
}();

// "00" .. "ff": a byte's two hex digits in one store.
constexpr auto kHexPairs = [] {
  std::array<char, 512> pairs{};
  for (std::size_t i = 0; i < 256; ++i) {
    pairs[2 * i] = kHexDigits[i >> 4];
    pairs[2 * i + 1] = kHexDigits[i & 0xF];
  }
  return pairs;
}();

// Writes `value` in decimal so that it ends just before `end`, with a decimal point
// `decimals` (0..9) digits from the right and at least one digit before the point; returns
// where the text starts. The caller appends it at once: one append per number.
char* write_scaled(char* end, std::uint64_t value, int decimals) {
  char* p = end;
  const auto pair = [&p](std::uint64_t two) {
    p -= 2;
    std::memcpy(p, &kDigitPairs[2 * two], 2);
  };
  int left = decimals;
  for (; left >= 2; left -= 2) {
    pair(value % 100);
    value /= 100;
  }
  if (left == 1) {
    *--p = static_cast<char>('0' + value % 10);
    value /= 10;
  }
  if (decimals > 0) *--p = '.';
  for (; value >= 100; value /= 100) pair(value % 100);
  if (value >= 10) {
    pair(value);
  } else {
    *--p = static_cast<char>('0' + value);
  }
  return p;
}

constexpr std::size_t kNumberText = 32;  // 20 digits, a sign and a point, with room

// `scaled` with a decimal point `decimals` digits from the right ("523", 1 -> "52.3"), and a
// minus sign first when asked.
void append_scaled(std::string& out, std::uint64_t scaled, int decimals, bool negative = false) {
  std::array<char, kNumberText> buf;
  char* end = buf.data() + buf.size();
  char* start = write_scaled(end, scaled, decimals);
  if (negative) *--start = '-';
  out.append(start, static_cast<std::size_t>(end - start));
}

// Splits epoch seconds into whole seconds and microseconds, rounding once. A capture's
// timestamp can lie far beyond any date (pcapng has 64 bits of them): it is held to what
// the microsecond count can represent (about the year 292,000) instead of overflowing it.
void split_time(double epoch_seconds, std::time_t& seconds, long& micros) {
  constexpr double kMaxMicros = 9.2e18;  // just under 2^63
  const double rounded = std::round(epoch_seconds * 1e6);
  const auto total = static_cast<long long>(
      std::isnan(rounded) ? 0 : std::clamp(rounded, -kMaxMicros, kMaxMicros));
  seconds = static_cast<std::time_t>(total / 1000000);
  micros = static_cast<long>(total % 1000000);
  if (micros < 0) {
    micros += 1000000;
    seconds -= 1;
  }
}

// std::llround for |x| < 2^52 without the library call: x - trunc(x) is exact there.
long long round_half_away(double x) {
  auto whole = static_cast<long long>(x);
  const double fraction = x - static_cast<double>(whole);
  if (fraction >= 0.5) ++whole;
  if (fraction <= -0.5) --whole;
  return whole;
}

// value * 10^decimals rounded from the exact binary value, ties to even, as to_chars rounds:
// for capture timestamps (1.7e15 microseconds), where the product in doubles would round.
// The caller keeps the result below 2^64 and value in [1, 2^53).
std::uint64_t exact_scaled(double value, int decimals) {
  __extension__ using Wide = unsigned __int128;
  static constexpr std::uint64_t kPowers10[] = {1,      10,      100,      1000,      10000,
                                                100000, 1000000, 10000000, 100000000, 1000000000};
  int exponent = 0;
  const double fraction = std::frexp(value, &exponent);  // value = fraction * 2^exponent
  const auto mantissa = static_cast<std::uint64_t>(std::ldexp(fraction, 53));
  const int shift = 53 - exponent;  // value = mantissa / 2^shift, 0 <= shift <= 52
  const Wide scaled = Wide{mantissa} * kPowers10[decimals];
  if (shift == 0) return static_cast<std::uint64_t>(scaled);
  auto whole = static_cast<std::uint64_t>(scaled >> shift);
  const Wide rest = scaled & ((Wide{1} << shift) - 1);
  const Wide half = Wide{1} << (shift - 1);
  if (rest > half || (rest == half && (whole & 1) != 0)) ++whole;
  return whole;
}

void append_two(std::string& out, int value) {
  out += static_cast<char>('0' + value / 10);
  out += static_cast<char>('0' + value % 10);
}

// hh:mm:ss.uuuuuu
void append_clock(std::string& out, const std::tm& tm, long micros) {
  append_two(out, tm.tm_hour);
  out += ':';
  append_two(out, tm.tm_min);
  out += ':';
  append_two(out, tm.tm_sec);
  out += '.';
  std::array<char, 8> digits{};
  for (int i = 5; i >= 0; --i) {
    digits[static_cast<std::size_t>(i)] = static_cast<char>('0' + micros % 10);
    micros /= 10;
  }
  out.append(digits.data(), 6);
}

}  // namespace

void append_uint(std::string& out, std::uint64_t value) {
  // Stations, function codes and lengths are mostly one or two digits.
  if (value < 10) {
    out += static_cast<char>('0' + value);
  } else if (value < 100) {
    out.append(&kDigitPairs[2 * value], 2);
  } else {
    append_scaled(out, value, 0);
  }
}

void append_int(std::string& out, std::int64_t value) {
  // The magnitude as unsigned: -INT64_MIN does not fit in int64.
  const std::uint64_t magnitude =
      value < 0 ? ~static_cast<std::uint64_t>(value) + 1 : static_cast<std::uint64_t>(value);
  append_scaled(out, magnitude, 0, value < 0);
}

void append_fixed(std::string& out, double value, int decimals) {
  static constexpr double kPowers[] = {1, 10, 100, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
  if (!std::isfinite(value)) value = 0;
  // Most readings are small scaled integers: integer arithmetic formats them far faster than
  // to_chars, with the same rounding. Larger ones take the general path.
  if (decimals >= 0 && decimals <= 9 && std::fabs(value) * kPowers[decimals] < 1e15) {
    const auto scaled = round_half_away(value * kPowers[decimals]);
    // A value that rounds to zero prints without a sign.
    append_scaled(out, static_cast<std::uint64_t>(scaled < 0 ? -scaled : scaled), decimals,
                  scaled < 0);
    return;
  }
  if (decimals >= 0 && decimals <= 9 && value > 0 && value * kPowers[decimals] < 1e19 &&
      value < 0x1p53) {
    append_scaled(out, exact_scaled(value, decimals), decimals);
    return;
  }
  std::array<char, 64> buf{};
  const auto r =
      std::to_chars(buf.data(), buf.data() + buf.size(), value, std::chars_format::fixed, decimals);
  out.append(buf.data(), r.ptr);
}

void append_hex(std::string& out, std::span<const std::uint8_t> bytes) {
  const std::size_t at = out.size();
  out.resize(at + 2 * bytes.size());
  char* p = out.data() + at;
  for (const std::uint8_t b : bytes) {
    std::memcpy(p, &kHexPairs[2 * b], 2);
    p += 2;
  }
}

void append_spaced_hex(std::string& out, std::span<const std::uint8_t> bytes) {
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    if (i > 0) out += ' ';
    out += kHexDigits[bytes[i] >> 4];
    out += kHexDigits[bytes[i] & 0xF];
  }
}

void append_hex_byte(std::string& out, std::uint8_t value) {
  static constexpr char kUpper[] = "0123456789ABCDEF";
  out += "0x";
  out += kUpper[value >> 4];
  out += kUpper[value & 0xF];
}

void append_time_of_day(std::string& out, double epoch_seconds) {
  std::time_t seconds = 0;
  long micros = 0;
  split_time(epoch_seconds, seconds, micros);
  std::tm tm{};
  gmtime_r(&seconds, &tm);
  append_clock(out, tm, micros);
}

void append_utc_date_time(std::string& out, double epoch_seconds) {
  std::time_t seconds = 0;
  long micros = 0;
  split_time(epoch_seconds, seconds, micros);
  std::tm tm{};
  gmtime_r(&seconds, &tm);
  append_int(out, std::int64_t{tm.tm_year} + 1900);
  out += '-';
  append_two(out, tm.tm_mon + 1);
  out += '-';
  append_two(out, tm.tm_mday);
  out += ' ';
  append_clock(out, tm, micros);
}

}  // namespace pvtap::analyzer
