#include "registers/inference_evidence.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>

namespace pvtap::detail {
namespace {

// Hint: a range of readings that suggests what a value is (data, not code paths).
struct Hint {
  double low, high;
  bool needs_change;  // only a value that moves (a constant 1.0 is no power factor)
  const char* text;
};
constexpr std::array kHints{
    Hint{180.0, 260.0, false, "a phase voltage?"},
    Hint{340.0, 460.0, false, "a line-to-line voltage?"},
    Hint{49.5, 50.5, false, "a grid frequency (50 Hz)?"},
    Hint{59.5, 60.5, false, "a grid frequency (60 Hz)?"},
    Hint{-1.0, 1.0, true, "a power factor?"},
};

}  // namespace

std::string hint_for(double min, double max, bool constant) {
  for (const Hint& h : kHints) {
    if (h.needs_change && constant) continue;
    if (min >= h.low && max <= h.high) {
      return words_of("%.4g..%.4g: %s", min, max, h.text);
    }
  }
  return {};
}

std::string format_words(std::string_view format, std::initializer_list<EvidenceArg> args) {
  std::string out;
  auto next = args.begin();
  for (std::size_t k = 0; k < format.size(); ++k) {
    if (format[k] != '%' || next == args.end()) {
      out += format[k];
      continue;
    }
    int width = 0, precision = -1;
    ++k;
    if (format[k] == '0') ++k;
    while (format[k] >= '0' && format[k] <= '9') width = width * 10 + (format[k++] - '0');
    if (format[k] == '.') {
      precision = 0;
      while (format[++k] >= '0' && format[k] <= '9') precision = precision * 10 + (format[k] - '0');
    }
    if (format[k] == 'z') ++k;
    const char conversion = format[k];
    const EvidenceArg& a = *next++;
    std::array<char, 64> buf{};
    char* end = buf.data();
    if (const auto* text = std::get_if<std::string_view>(&a)) {
      out += *text;
      continue;
    }
    if (const auto* d = std::get_if<double>(&a)) {
      const auto style = conversion == 'g' ? std::chars_format::general : std::chars_format::fixed;
      end =
          std::to_chars(buf.data(), buf.data() + buf.size(), *d, style, std::max(precision, 0)).ptr;
    } else if (const auto* i = std::get_if<std::int64_t>(&a)) {
      end = std::to_chars(buf.data(), buf.data() + buf.size(), *i).ptr;
    } else {
      end = std::to_chars(buf.data(), buf.data() + buf.size(), std::get<std::uint64_t>(a),
                          conversion == 'X' ? 16 : 10)
                .ptr;
      if (conversion == 'X') {
        for (char* c = buf.data(); c != end; ++c) *c = static_cast<char>(std::toupper(*c));
      }
    }
    for (auto n = static_cast<int>(end - buf.data()); n < width; ++n) out += '0';
    out.append(buf.data(), end);
  }
  return out;
}

}  // namespace pvtap::detail
