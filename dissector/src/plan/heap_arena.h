// HeapArena: an Arena over heap blocks owned by its holder and freed with it, for running the
// plan outside Wireshark (unit tests, the fuzz target); the plugin hands pinfo->pool instead.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "plan/arena.h"

namespace pvtap::dissector {

class HeapArena {
 public:
  Arena arena() { return {&HeapArena::allocate, this}; }

 private:
  static void* allocate(void* self, std::size_t size) {
    constexpr std::size_t unit = sizeof(std::max_align_t);
    auto& blocks = static_cast<HeapArena*>(self)->blocks_;
    blocks.push_back(std::make_unique<std::max_align_t[]>((size + unit - 1) / unit));
    return blocks.back().get();
  }

  std::vector<std::unique_ptr<std::max_align_t[]>> blocks_;
};

}  // namespace pvtap::dissector
