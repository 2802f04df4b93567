// Arena: where plans and tree descriptions live: memory freed all at once, without destructors.
#pragma once

#include <cstddef>
#include <cstring>
#include <new>
#include <string_view>
#include <type_traits>

namespace pvtap::dissector {

// The plugin hands pinfo->pool (wmem frees a packet's memory with the packet and runs no
// destructor), a test its own blocks; so only plain data goes in. `allocate` returns memory
// aligned for any type, or does not return.
struct Arena {
  void* (*allocate)(void* state, std::size_t size) = nullptr;
  void* state = nullptr;

  // A NUL-terminated copy of `text`.
  const char* copy(std::string_view text) const {
    auto* out = static_cast<char*>(allocate(state, text.size() + 1));
    if (!text.empty()) std::memcpy(out, text.data(), text.size());
    out[text.size()] = '\0';
    return out;
  }

  // `count` value-initialized T (null for none).
  template <typename T>
  T* make_array(std::size_t count) const {
    static_assert(std::is_trivially_destructible_v<T>);
    if (count == 0) return nullptr;
    auto* first = static_cast<T*>(allocate(state, sizeof(T) * count));
    for (std::size_t i = 0; i < count; ++i) new (first + i) T{};
    return first;
  }
};

}  // namespace pvtap::dissector
