// Builder: gathers the items of one tree description before they go to the arena.
#pragma once

#include <algorithm>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tree/tree_description.h"

namespace pvtap::dissector {

// Depths: the top item, the frame's subtree, the subtrees of its fields.
inline constexpr std::uint8_t kTop = 0;
inline constexpr std::uint8_t kFrame = 1;
inline constexpr std::uint8_t kField = 2;

// A text of the plan, which a plan made by hand may lack.
inline std::string_view text_of(const char* text) {
  return text != nullptr ? std::string_view(text) : std::string_view();
}

// printf-style text, for the sentences that print numbers in hex.
[[gnu::format(printf, 1, 2)]] inline std::string printed(const char* format, ...) {
  char text[160];
  va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(text, sizeof text, format, args);
  va_end(args);
  return std::string(text,
                     static_cast<std::size_t>(std::clamp(n, 0, static_cast<int>(sizeof text) - 1)));
}

// Builder: the items of one description, gathered before they are copied to the arena.
class Builder {
 public:
  explicit Builder(const DescriptionContext& ctx) : ctx_(ctx) {}

  const DescriptionContext& ctx() const { return ctx_; }
  const char* text(std::string_view t) const { return ctx_.arena.copy(t); }

  // Adds an item and returns its index.
  std::uint32_t add(const TreeItem& item) {
    items_.push_back(item);
    return static_cast<std::uint32_t>(items_.size() - 1);
  }
  TreeItem& item(std::uint32_t index) { return items_[index]; }

  // A field's value at a place in the frame; skipped when the frame has no such place.
  std::optional<std::uint32_t> uint(TreeField field, FieldSpan s, std::uint32_t value,
                                    std::uint8_t depth = kFrame) {
    if (!s.present()) return std::nullopt;
    return add(field_item(field, s, value, depth));
  }
  // A value worked out rather than read: no place in the frame.
  std::uint32_t generated_uint(TreeField field, std::uint32_t value) {
    TreeItem item = field_item(field, FieldSpan{}, value, kFrame);
    item.generated = true;
    return add(item);
  }
  // An expert info on an item that may not have been added (its field absent).
  void expert_on(std::optional<std::uint32_t> target, TreeExpert expert, std::string_view message) {
    TreeItem item;
    item.kind = ItemKind::Expert;
    item.expert = expert;
    item.text = text(message);
    item.target = target ? static_cast<std::int32_t>(*target) : -1;
    add(item);
  }
  // An expert info with an item of its own; a null message shows the expert's summary.
  std::uint32_t expert_item(TreeExpert expert, FieldSpan s, const char* message) {
    TreeItem item;
    item.kind = ItemKind::ExpertItem;
    item.expert = expert;
    item.depth = kFrame;
    item.offset = s.offset;
    item.length = s.length;
    item.text = message;
    return add(item);
  }

  TreeDescription finish(Dialect dialect) const {
    TreeItem* items = ctx_.arena.make_array<TreeItem>(items_.size());
    std::copy(items_.begin(), items_.end(), items);
    return {items, items_.size(), dialect};
  }

 private:
  static TreeItem field_item(TreeField field, FieldSpan s, std::uint32_t value,
                             std::uint8_t depth) {
    TreeItem item;
    item.field = field;
    item.depth = depth;
    item.offset = s.offset;
    item.length = s.length;
    item.uint = value;
    return item;
  }

  const DescriptionContext& ctx_;
  std::vector<TreeItem> items_;
};

}  // namespace pvtap::dissector
