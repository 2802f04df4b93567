// The words of an inferred value's evidence: printf-style text without printf, and the hints
// a value's range gives.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>

namespace pvtap::detail {

// The evidence is written printf-style, without printf (the core does no I/O): the
// conversions used here, %u %d %zu %s %.Nf %.Ng and %04X, each taking the next argument.
using EvidenceArg = std::variant<std::int64_t, std::uint64_t, double, std::string_view>;

std::string format_words(std::string_view format, std::initializer_list<EvidenceArg> args);

inline EvidenceArg to_arg(double x) {
  return x;
}
inline EvidenceArg to_arg(const char* x) {
  return std::string_view(x);
}
template <typename T>
EvidenceArg to_arg(T x) {
  if constexpr (std::is_signed_v<T>) {
    return static_cast<std::int64_t>(x);
  } else {
    return static_cast<std::uint64_t>(x);
  }
}

template <typename... Args>
std::string words_of(const char* format, Args... args) {
  return format_words(format, {to_arg(args)...});
}

// What the range min..max of a value suggests it is ("a phase voltage?"), or nothing.
std::string hint_for(double min, double max, bool constant);

}  // namespace pvtap::detail
