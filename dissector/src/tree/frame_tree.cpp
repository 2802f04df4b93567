#include "tree/frame_tree.h"

#include <epan/expert.h>
#include <epan/proto.h>

#include "fields/register_fields.h"

namespace pvtap::dissector {
namespace {

static_assert(static_cast<int>(CheckStatus::Bad) == PROTO_CHECKSUM_E_BAD);
static_assert(static_cast<int>(CheckStatus::Good) == PROTO_CHECKSUM_E_GOOD);
static_assert(static_cast<int>(CheckStatus::Unverified) == PROTO_CHECKSUM_E_UNVERIFIED);
static_assert(static_cast<int>(CheckStatus::NotPresent) == PROTO_CHECKSUM_E_NOT_PRESENT);

constexpr std::size_t kDepths = 4;

// Adder: one description going into the tree. Every member is plain: a longjmp out of a
// Wireshark call leaves nothing to destroy.
struct Adder {
  const TreeTarget& t;
  Dialect dialect;
  proto_item** added;               // by description index, in pinfo->pool
  proto_tree* trees[kDepths] = {};  // where the items of each depth go

  int field_id(const TreeItem& item) const {
    if (item.field == TreeField::Protocol) return t.protocol->proto;
    if (item.field == TreeField::Modbus) return t.protocol->hf.of(item.modbus);
    const RegisterField* f = item.def != nullptr ? register_field(dialect, item.def) : nullptr;
    if (item.field == TreeField::RegisterValue) return f != nullptr ? f->hf : -1;
    if (item.field == TreeField::RegisterFlag) return f != nullptr ? f->bits[item.bit] : -1;
    return t.protocol->hf.of(item.field);
  }

  int subtree_id(const TreeItem& item) const {
    if (item.subtree != Subtree::Flags) return t.protocol->ett.of(item.subtree);
    const RegisterField* f = register_field(dialect, item.def);
    return f != nullptr ? f->ett : -1;
  }

  proto_item* add_value(proto_tree* tree, int id, const TreeItem& i) const {
    const gint start = t.offset + i.offset;
    switch (i.type) {
      case ValueType::Bytes:
        return proto_tree_add_item(tree, id, t.tvb, start, i.length, ENC_NA);
      case ValueType::Boolean:
        return proto_tree_add_boolean(tree, id, t.tvb, start, i.length, i.uint);
      case ValueType::Double:
        if (i.text == nullptr)
          return proto_tree_add_double(tree, id, t.tvb, start, i.length, i.number);
        return proto_tree_add_double_format(tree, id, t.tvb, start, i.length, i.number, "%s",
                                            i.text);
      case ValueType::String:
        if (i.form == LabelForm::Default) {
          return proto_tree_add_string(tree, id, t.tvb, start, i.length, i.string);
        }
        return proto_tree_add_string_format(tree, id, t.tvb, start, i.length, i.string, "%s",
                                            i.text);
      case ValueType::Time: {
        nstime_t time;
        time.secs = static_cast<time_t>(i.time.secs);
        time.nsecs = i.time.nsecs;
        return proto_tree_add_time(tree, id, t.tvb, start, i.length, &time);
      }
      case ValueType::Uint:
        break;
    }
    switch (i.form) {
      case LabelForm::Value:
        return proto_tree_add_uint_format_value(tree, id, t.tvb, start, i.length, i.uint, "%s",
                                                i.text);
      case LabelForm::Whole:
        return proto_tree_add_uint_format(tree, id, t.tvb, start, i.length, i.uint, "%s", i.text);
      case LabelForm::Default:
        break;
    }
    return proto_tree_add_uint(tree, id, t.tvb, start, i.length, i.uint);
  }

  // Fields a protocol does not register (-1) are skipped rather than asserted on.
  proto_item* add_field(proto_tree* tree, const TreeItem& i) const {
    const int id = field_id(i);
    if (id < 0) return nullptr;
    proto_item* item = add_value(tree, id, i);
    if (i.generated) proto_item_set_generated(item);
    return item;
  }

  void raise(const TreeItem& i) const {
    proto_item* item = i.target >= 0 ? added[i.target] : nullptr;
    expert_field* ei = t.protocol->ei.of(i.expert);
    if (ei == nullptr) return;
    if (i.text == nullptr) {
      expert_add_info(t.pinfo, item, ei);
    } else {
      expert_add_info_format(t.pinfo, item, ei, "%s", i.text);
    }
  }

  proto_item* add_expert_item(proto_tree* tree, const TreeItem& i) const {
    expert_field* ei = t.protocol->ei.of(i.expert);
    if (ei == nullptr) return nullptr;
    const gint start = t.offset + i.offset;
    if (i.text == nullptr) return proto_tree_add_expert(tree, t.pinfo, ei, t.tvb, start, i.length);
    return proto_tree_add_expert_format(tree, t.pinfo, ei, t.tvb, start, i.length, "%s", i.text);
  }

  proto_item* add(const TreeItem& i) {
    if (i.depth >= kDepths) return nullptr;  // deeper than any subtree a description opens
    proto_tree* tree = trees[i.depth];
    proto_item* item = nullptr;
    switch (i.kind) {
      case ItemKind::Expert:
        raise(i);
        return nullptr;
      case ItemKind::ExpertItem:
        item = add_expert_item(tree, i);
        break;
      case ItemKind::Field:
        item = add_field(tree, i);
        break;
    }
    if (i.appended != nullptr) proto_item_append_text(item, "%s", i.appended);
    // The items one level deeper that follow go under this one, or nowhere.
    if (i.depth + 1u < kDepths) {
      const int ett = subtree_id(i);
      trees[i.depth + 1] = ett >= 0 ? proto_item_add_subtree(item, ett) : nullptr;
    }
    return item;
  }
};

}  // namespace

void add_tree(const TreeTarget& target, const TreeDescription& description) {
  if (description.count == 0) return;
  Adder adder{target, description.dialect,
              wmem_alloc_array(target.pinfo->pool, proto_item*, description.count)};
  adder.trees[0] = target.tree;
  for (std::size_t i = 0; i < description.count; ++i) {
    adder.added[i] = adder.add(description.items[i]);
  }
}

}  // namespace pvtap::dissector
