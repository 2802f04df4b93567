// Result: the one error style of the core's public API, a value or what prevented it.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace pvtap {

// The text of a diagnostic that is already words (a short static description).
inline std::string diagnostic_text(std::string_view why) {
  return std::string(why);
}

// Result: a value, or the diagnostics that explain why there is none. `Diagnostics` is what
// the operation can say: a static description (std::string_view, nothing allocated, for
// per-frame work) or a list of located problems (a map file's). error_text() renders them
// through diagnostic_text(), found next to the diagnostic type.
template <typename T, typename Diagnostics = std::string_view>
class Result {
 public:
  // Implicit, so that a function returns its value as it is; built in place (a Frame is
  // large and is parsed once per frame).
  Result(const T& value) : value_(value) {}        // NOLINT(google-explicit-constructor)
  Result(T&& value) : value_(std::move(value)) {}  // NOLINT(google-explicit-constructor)
  static Result failure(Diagnostics why) {
    Result r;
    r.diagnostics_ = std::move(why);
    return r;
  }

  bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }
  // Only when ok().
  const T& value() const& { return *value_; }
  T& value() & { return *value_; }
  T&& value() && { return std::move(*value_); }
  const T* operator->() const { return &*value_; }
  // Empty when ok().
  const Diagnostics& diagnostics() const { return diagnostics_; }
  std::string error_text() const { return diagnostic_text(diagnostics_); }

 private:
  Result() = default;
  std::optional<T> value_;
  Diagnostics diagnostics_{};
};

}  // namespace pvtap
