// InverterProtocol: the ids, handles and settings of one of the plugin's two protocols.
#pragma once

#include <epan/expert.h>
#include <epan/packet.h>

#include <array>
#include <cstddef>

#include "plan/field_table.h"
#include "pvtap/codec/dialect.h"
#include "wireshark_api/preference_types.h"

namespace pvtap::dissector {

// Filled: an array of ids before Wireshark has assigned them.
template <typename T, std::size_t N>
constexpr std::array<T, N> filled(const T& unassigned) {
  std::array<T, N> ids{};
  ids.fill(unassigned);
  return ids;
}

// FieldIds: the ids of a protocol's fields, by line of the field tables; -1 where the
// protocol registered none (invascii has no Modbus fields, for one).
struct FieldIds {
  std::array<int, kFrameFieldCount> frame = filled<int, kFrameFieldCount>(-1);
  std::array<int, kModbusFieldCount> modbus = filled<int, kModbusFieldCount>(-1);

  // -1 too for the items whose ids come from elsewhere (TreeField::None and after).
  int of(TreeField field) const {
    const auto i = static_cast<std::size_t>(field);
    return i < frame.size() ? frame[i] : -1;
  }
  int of(ModbusField field) const {
    const auto i = static_cast<std::size_t>(field);
    return i < modbus.size() ? modbus[i] : -1;
  }
};

// ExpertIds: the expert infos of a protocol, by line of the expert tables.
struct ExpertIds {
  std::array<expert_field, kExpertCount> all = filled<expert_field, kExpertCount>(EI_INIT);

  // Null for TreeExpert::None.
  expert_field* of(TreeExpert expert) {
    const auto i = static_cast<std::size_t>(expert);
    return i < all.size() ? &all[i] : nullptr;
  }
};

// SubtreeIds: the ett ids of a protocol's subtrees, by line of PVTAP_SUBTREES.
struct SubtreeIds {
  std::array<int, kSubtreeCount> all = filled<int, kSubtreeCount>(-1);

  // -1 too for the subtrees whose ids come from elsewhere (Subtree::None and after).
  int of(Subtree subtree) const {
    const auto i = static_cast<std::size_t>(subtree);
    return i < all.size() ? all[i] : -1;
  }
};

// ProtocolSettings: preference values; Wireshark writes them through pointers.
struct ProtocolSettings {
  PreferenceBool verify_check = true;
  PreferenceBool desegment = true;
  guint reply_timeout_ms = 1000;
  guint baud = 9600;          // of the bus behind the gateway: wire times of segments
  guint gateway_gap_ms = 50;  // silence between segments that proves a frame boundary
  gint gsl_ids = 0;           // GslIdReading, invrtu only
  gint pair_rule = 0;         // 0 binary, 1 decimal; invrtu only
};

// InverterProtocol: one protocol (invascii or invrtu) and everything registered for it.
struct InverterProtocol {
  const char* name;         // "Inverter RTU protocol"
  const char* short_name;   // "invRTU"
  const char* filter_name;  // "invrtu"
  const char* check_name;   // "CRC" or "Checksum"
  const char* check_key;    // "crc" or "checksum"
  const char* check_word;   // "CRC" or "checksum", inside sentences
  DialectSet dialects;
  int proto = -1;
  int tap = -1;
  FieldIds hf{};
  ExpertIds ei{};
  SubtreeIds ett{};
  ProtocolSettings settings{};
  dissector_handle_t stream_handle = nullptr;    // TCP: reassembles across segments
  dissector_handle_t datagram_handle = nullptr;  // UDP, records, RTAC serial payloads
};

InverterProtocol& rtu_protocol();
InverterProtocol& ascii_protocol();
InverterProtocol& protocol_of(Dialect d);

}  // namespace pvtap::dissector
