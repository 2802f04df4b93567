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

// The id of a common field; -1 for the protocol's fields it does not register.
int common_field_id(const CommonFields& hf, TreeField field) {
  switch (field) {
    case TreeField::Dialect:
      return hf.dialect;
    case TreeField::Role:
      return hf.role;
    case TreeField::Station:
      return hf.station;
    case TreeField::Function:
      return hf.function;
    case TreeField::Start:
      return hf.start;
    case TreeField::Count:
      return hf.count;
    case TreeField::ByteCount:
      return hf.byte_count;
    case TreeField::Device:
      return hf.device;
    case TreeField::DeviceType:
      return hf.device_type;
    case TreeField::DeviceSerial:
      return hf.device_serial;
    case TreeField::ExceptionCode:
      return hf.exception_code;
    case TreeField::ErrorBody:
      return hf.error_body;
    case TreeField::Word:
      return hf.word;
    case TreeField::Check:
      return hf.check;
    case TreeField::CheckStatus:
      return hf.check_status;
    case TreeField::CheckExpected:
      return hf.check_expected;
    case TreeField::Noise:
      return hf.noise;
    case TreeField::UnknownFunction:
      return hf.unknown_function;
    case TreeField::RequestIn:
      return hf.request_in;
    case TreeField::ResponseIn:
      return hf.response_in;
    case TreeField::ResponseTime:
      return hf.response_time;
    case TreeField::Undecoded:
      return hf.undecoded;
    case TreeField::ExpectedCount:
      return hf.expected_count;
    case TreeField::UnansweredRequest:
      return hf.unanswered_request;
    case TreeField::TimeoutIn:
      return hf.timeout_in;
    case TreeField::None:
    case TreeField::Protocol:
    case TreeField::Modbus:
    case TreeField::RegisterValue:
    case TreeField::RegisterFlag:
      break;
  }
  return -1;
}

expert_field* expert_of(ExpertFields& ei, TreeExpert expert) {
  switch (expert) {
    case TreeExpert::BadCheck:
      return &ei.bad_check;
    case TreeExpert::Malformed:
      return &ei.malformed;
    case TreeExpert::Noise:
      return &ei.noise;
    case TreeExpert::UnknownFunction:
      return &ei.unknown_function;
    case TreeExpert::Exception:
      return &ei.exception;
    case TreeExpert::Unanswered:
      return &ei.unanswered;
    case TreeExpert::Unsolicited:
      return &ei.unsolicited;
    case TreeExpert::LateReply:
      return &ei.late_reply;
    case TreeExpert::Duplicate:
      return &ei.duplicate;
    case TreeExpert::AddressConflict:
      return &ei.address_conflict;
    case TreeExpert::Echo:
      return &ei.echo;
    case TreeExpert::CountMismatch:
      return &ei.count_mismatch;
    case TreeExpert::RoleCorrected:
      return &ei.role_corrected;
    case TreeExpert::StartUnknown:
      return &ei.start_unknown;
    case TreeExpert::StartAssumed:
      return &ei.start_assumed;
    case TreeExpert::ValueNote:
      return &ei.value_note;
    case TreeExpert::ValueSuspicious:
      return &ei.value_suspicious;
    case TreeExpert::QuantityProblem:
      return &ei.quantity_problem;
    case TreeExpert::DialectChanged:
      return &ei.dialect_changed;
    case TreeExpert::BroadcastNotAllowed:
      return &ei.broadcast_not_allowed;
    case TreeExpert::WriteCountProblem:
      return &ei.write_count_problem;
    case TreeExpert::None:
      break;
  }
  return nullptr;
}

// Adder: one description going into the tree. Every member is plain: a longjmp out of a
// Wireshark call leaves nothing to destroy.
struct Adder {
  const TreeTarget& t;
  Dialect dialect;
  proto_item** added;               // by description index, in pinfo->pool
  proto_tree* trees[kDepths] = {};  // where the items of each depth go

  int field_id(const TreeItem& item) const {
    if (item.field == TreeField::Protocol) return t.protocol->proto;
    if (item.field == TreeField::Modbus) {
      return t.protocol->hf.modbus[static_cast<std::size_t>(item.modbus)];
    }
    const RegisterField* f = item.def != nullptr ? register_field(dialect, item.def) : nullptr;
    if (item.field == TreeField::RegisterValue) return f != nullptr ? f->hf : -1;
    if (item.field == TreeField::RegisterFlag) return f != nullptr ? f->bits[item.bit] : -1;
    return common_field_id(t.protocol->hf, item.field);
  }

  int subtree_id(const TreeItem& item) const {
    switch (item.subtree) {
      case Subtree::Frame:
        return t.protocol->ett.frame;
      case Subtree::Noise:
        return t.protocol->ett.noise;
      case Subtree::Device:
        return t.protocol->ett.device;
      case Subtree::Coils:
        return t.protocol->ett.coils;
      case Subtree::Coil:
        return t.protocol->ett.coil;
      case Subtree::DeviceObject:
        return t.protocol->ett.device_object;
      case Subtree::MapEntry:
        return t.protocol->ett.map_entry;
      case Subtree::Flags: {
        const RegisterField* f = register_field(dialect, item.def);
        return f != nullptr ? f->ett : -1;
      }
      case Subtree::None:
        break;
    }
    return -1;
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
    expert_field* ei = expert_of(t.protocol->ei, i.expert);
    if (i.text == nullptr) {
      expert_add_info(t.pinfo, item, ei);
    } else {
      expert_add_info_format(t.pinfo, item, ei, "%s", i.text);
    }
  }

  proto_item* add_expert_item(proto_tree* tree, const TreeItem& i) const {
    expert_field* ei = expert_of(t.protocol->ei, i.expert);
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
