// FuzzInput: reads the fuzzer's bytes as small structured values (a minimal FuzzedDataProvider
// that builds with g++ as well, so that the corpus replay tests need no clang).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>
#include <vector>

namespace pvtap::fuzz {

class FuzzInput {
 public:
  FuzzInput(const std::uint8_t* data, std::size_t size) : bytes_(data, size) {}

  bool empty() const { return at_ >= bytes_.size(); }
  std::size_t remaining() const { return bytes_.size() - at_; }

  // The next byte, or 0 when the input is used up.
  std::uint8_t byte() { return empty() ? 0 : bytes_[at_++]; }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = (v << 8) | byte();
    return v;
  }
  // Up to `n` of the next bytes (fewer at the end of the input).
  std::span<const std::uint8_t> take(std::size_t n) {
    const std::size_t k = n < remaining() ? n : remaining();
    const auto out = bytes_.subspan(at_, k);
    at_ += k;
    return out;
  }
  std::span<const std::uint8_t> rest() { return take(remaining()); }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t at_ = 0;
};

// Fails the run (a finding) when an invariant does not hold; works without assert().
#define PVTAP_FUZZ_CHECK(condition)                                                          \
  do {                                                                                       \
    if (!(condition)) {                                                                      \
      std::fprintf(stderr, "%s:%d: invariant failed: %s\n", __FILE__, __LINE__, #condition); \
      std::abort();                                                                          \
    }                                                                                        \
  } while (0)

// Command-line arguments as a fuzz input spells them: NUL-separated.
inline std::vector<std::string> nul_separated_arguments(const std::uint8_t* data,
                                                        std::size_t size) {
  std::vector<std::string> args(1);
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == 0) {
      args.emplace_back();
    } else {
      args.back() += static_cast<char>(data[i]);
    }
  }
  return args;
}

}  // namespace pvtap::fuzz
