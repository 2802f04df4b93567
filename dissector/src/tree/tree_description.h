// TreeDescription: what the protocol tree shows of one frame or run of noise, as plain data.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <type_traits>

#include "plan/arena.h"
#include "plan/field_table.h"
#include "plan/frame_plan.h"
#include "plan/frame_record.h"
#include "pvtap/codec/unknown_function_frame.h"

namespace pvtap::dissector {

// ItemKind: what adding the item does.
enum class ItemKind : std::uint8_t {
  Field,       // adds a field's item
  Expert,      // raises an expert info on the item `target` (which may be absent)
  ExpertItem,  // adds an expert info's item of its own, at `offset`
};

// ValueType: the value an item holds (and the call that adds it).
enum class ValueType : std::uint8_t {
  Bytes,    // the bytes at the item's place
  Uint,     // `uint`
  Boolean,  // bit of `uint` (register flags)
  Double,   // `number`
  String,   // `string`
  Time,     // `time`
};

// LabelForm: how an item's label is written.
enum class LabelForm : std::uint8_t {
  Default,  // the field's name and its value, as Wireshark writes them
  Value,    // the field's name, then `text` for its value
  Whole,    // `text` is the whole label
};

// CheckStatus: the value of the check status field, Wireshark's PROTO_CHECKSUM_E_* values.
// As Wireshark's proto_checksum_vals; NotPresent: a carried frame (Modbus/TCP) has none.
enum class CheckStatus : std::uint32_t { Bad = 0, Good = 1, Unverified = 2, NotPresent = 3 };

// RelativeTime: a time difference, as Wireshark's nstime_t holds it.
struct RelativeTime {
  std::int64_t secs = 0;
  std::int32_t nsecs = 0;
};

// TreeItem: one step of building the tree, in the order they are taken.
struct TreeItem {
  ItemKind kind = ItemKind::Field;
  TreeField field = TreeField::None;
  TreeExpert expert = TreeExpert::None;
  ValueType type = ValueType::Uint;
  LabelForm form = LabelForm::Default;
  Subtree subtree = Subtree::None;
  std::uint8_t depth = 0;   // 0: the top item; n: in the subtree opened last at depth n - 1
  bool generated = false;   // not in the bytes: Wireshark shows it in brackets
  std::int32_t offset = 0;  // within the frame or noise run
  std::int32_t length = 0;
  std::uint32_t uint = 0;
  double number = 0;
  RelativeTime time;
  const char* string = nullptr;
  const char* text = nullptr;        // the label's text; experts: the message (null: the summary)
  const char* appended = nullptr;    // added to the label once the item is made
  const RegisterDef* def = nullptr;  // RegisterValue and RegisterFlag
  std::uint8_t bit = 0;              // RegisterFlag
  ModbusField modbus = ModbusField::SubFunction;  // Modbus
  std::int32_t target = -1;  // Expert: index of the item it is raised on (-1: none)
};

// TreeDescription: the items of one frame or noise run, in an Arena.
struct TreeDescription {
  const TreeItem* items = nullptr;
  std::size_t count = 0;
  Dialect dialect = kDefaultDialect;  // register fields are those of this dialect

  const TreeItem* begin() const { return items; }
  const TreeItem* end() const { return items + count; }
};

static_assert(std::is_trivially_destructible_v<TreeItem>);

// DescriptionContext: what a description needs besides the plan and the record.
struct DescriptionContext {
  Arena arena;                         // for the items and their texts
  std::int32_t length = 0;             // the frame's or noise run's bytes
  bool visited = false;                // a later pass, which knows where a timeout was announced
  const char* check_word = "CRC";      // "CRC" or "checksum", inside sentences
  std::uint32_t reply_timeout_ms = 0;  // the reply timeout the session judged by (0: unknown)
};

// The frame's subtree, its expert infos and its links to the matching frames. Never throws:
// empty when memory runs out.
TreeDescription describe_frame(const FramePlan& plan, const FrameRecord& record,
                               const DescriptionContext& ctx) noexcept;

// A noise item; `unknown` is set when the noise is a whole frame of an unknown function.
TreeDescription describe_noise(const std::optional<UnknownFunctionFrame>& unknown,
                               const DescriptionContext& ctx) noexcept;

// The announcement, on the packet where it became known, that `request` got no reply: the
// one place its verdict is shown, so that a first pass (a live capture) shows it as a later
// pass does.
TreeDescription describe_timeout(const FrameRecord& request,
                                 const DescriptionContext& ctx) noexcept;

}  // namespace pvtap::dissector
