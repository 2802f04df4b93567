#include "registration/mbap_entry.h"

#include <epan/conversation.h>
#include <epan/expert.h>
#include <epan/packet.h>
#include <epan/proto_data.h>

#include <epan/dissectors/packet-tcp.h>

#include <span>

#include "fields/field_list.h"
#include "protocol/inverter_protocol.h"
#include "pvtap/carriers/mbap_structure.h"
#include "stream/call_view.h"
#include "stream/mbap_track.h"
#include "stream/piece_display.h"

namespace pvtap::dissector {
namespace {

struct MbapProtocol {
  int proto = -1;
  int transaction = -1;
  int protocol_id = -1;
  int length = -1;
  int unit = -1;
  int ett = -1;
  expert_field bad_header = EI_INIT;
  dissector_handle_t handle = nullptr;
};

MbapProtocol g_mbap;

// Proto data keys of a packet: its ADU count so far (packet pool), the record of each ADU
// (file scope) from kRecordKey on, and the timeouts each ADU's call announces from
// kAnnouncementKey on.
constexpr guint32 kCountKey = 0;
constexpr guint32 kRecordKey = 1;
constexpr guint32 kAnnouncementKey = 0x10000;

// The requests one ADU's call announces as unanswered (file scope, noted on the first pass).
struct Announcements {
  FrameRecord** requests = nullptr;
  std::uint32_t count = 0;
};

guint32 next_adu_index(packet_info* pinfo) {
  auto* count =
      static_cast<guint32*>(p_get_proto_data(pinfo->pool, pinfo, g_mbap.proto, kCountKey));
  if (count == nullptr) {
    count = static_cast<guint32*>(wmem_alloc0(pinfo->pool, sizeof(guint32)));
    p_add_proto_data(pinfo->pool, pinfo, g_mbap.proto, kCountKey, count);
  }
  return (*count)++;
}

MbapTrack& track_of(packet_info* pinfo) {
  conversation_t* conversation = find_or_create_conversation(pinfo);
  auto* track = static_cast<MbapTrack*>(conversation_get_proto_data(conversation, g_mbap.proto));
  if (track == nullptr) {
    track = new_mbap_track(rtu_protocol().settings);
    conversation_add_proto_data(conversation, g_mbap.proto, track);
  }
  return *track;
}

// The gateway is the side on the port Decode As (or the preference) matched.
Direction direction_of(const packet_info* pinfo) {
  return pinfo->destport == pinfo->match_uint ? Direction::ToSlave : Direction::FromSlave;
}

// The record of this ADU (the `index`th of the packet): fed to the conversation's track on the
// first pass, kept after.
FrameRecord* record_of(packet_info* pinfo, guint32 index, std::span<const std::uint8_t> adu) {
  const guint32 key = kRecordKey + index;
  auto* r =
      static_cast<FrameRecord*>(p_get_proto_data(wmem_file_scope(), pinfo, g_mbap.proto, key));
  if (r != nullptr || PINFO_FD_VISITED(pinfo)) return r;
  r = track_of(pinfo).feed(direction_of(pinfo), adu, nstime_to_sec(&pinfo->abs_ts));
  p_add_proto_data(wmem_file_scope(), pinfo, g_mbap.proto, key, r);
  return r;
}

// The timeouts this ADU's call announces: taken from the track on the first pass (the ones its
// time made due), the same ones on every later pass.
const Announcements* announcements_of(packet_info* pinfo, guint32 index) {
  const guint32 key = kAnnouncementKey + index;
  auto* a =
      static_cast<Announcements*>(p_get_proto_data(wmem_file_scope(), pinfo, g_mbap.proto, key));
  if (a != nullptr || PINFO_FD_VISITED(pinfo)) return a;
  std::uint32_t count = 0;
  FrameRecord** requests = announce_timeouts(pinfo, track_of(pinfo).timeouts(), count);
  if (requests == nullptr) return nullptr;
  a = wmem_new0(wmem_file_scope(), Announcements);
  a->requests = requests;
  a->count = count;
  p_add_proto_data(wmem_file_scope(), pinfo, g_mbap.proto, key, a);
  return a;
}

// One ADU, whole (TCP reassembled it): the copy is parsed before any tree call may longjmp.
int dissect_adu(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void*) {
  const guint n = tvb_captured_length(tvb);
  const auto* data = static_cast<const guint8*>(tvb_memdup(pinfo->pool, tvb, 0, n));
  const std::span<const std::uint8_t> adu(data, n);
  const auto header = read_mbap_header(adu);
  const bool plausible =
      header && plausible_mbap_header(*header) && adu.size() == kMbapCarrierBytes + header->length;
  const guint32 index = next_adu_index(pinfo);
  FrameRecord* record = plausible ? record_of(pinfo, index, adu) : nullptr;
  proto_item* item = proto_tree_add_item(tree, g_mbap.proto, tvb, 0, kMbapHeaderBytes - 1, ENC_NA);
  proto_tree* sub = proto_item_add_subtree(item, g_mbap.ett);
  proto_tree_add_item(sub, g_mbap.transaction, tvb, 0, 2, ENC_BIG_ENDIAN);
  proto_tree_add_item(sub, g_mbap.protocol_id, tvb, 2, 2, ENC_BIG_ENDIAN);
  proto_tree_add_item(sub, g_mbap.length, tvb, 4, 2, ENC_BIG_ENDIAN);
  proto_tree_add_item(sub, g_mbap.unit, tvb, 6, 1, ENC_BIG_ENDIAN);
  if (record == nullptr) {
    col_set_str(pinfo->cinfo, COL_PROTOCOL, "invMBAP");
    col_add_fstr(pinfo->cinfo, COL_INFO, "MBAP header that lied: %u bytes skipped", n);
    expert_add_info_format(pinfo, item, &g_mbap.bad_header,
                           "MBAP header that lied (protocol id not 0, or a length that does "
                           "not fit): %u bytes skipped",
                           n);
    return static_cast<int>(n);
  }
  const auto frame = adu.subspan(kMbapCarrierBytes);
  show_frame(TreeTarget{tvb, pinfo, tree, static_cast<int>(kMbapCarrierBytes),
                        static_cast<int>(frame.size()), &rtu_protocol()},
             frame, *record);
  if (const Announcements* a = announcements_of(pinfo, index)) {
    for (std::uint32_t i = 0; i < a->count; ++i) show_timeout(*a->requests[i], tvb, pinfo, tree);
  }
  return static_cast<int>(n);
}

// The ADU's length from its header; a header that cannot be true gives up the rest of the
// segment, as pvtap audit's reader does.
guint adu_length(packet_info*, tvbuff_t* tvb, int offset, void*) {
  const guint16 protocol_id = tvb_get_ntohs(tvb, offset + 2);
  const guint16 length = tvb_get_ntohs(tvb, offset + 4);
  if (protocol_id != 0 || length < kMbapMinLength || length > kMbapMaxLength) {
    return static_cast<guint>(tvb_reported_length_remaining(tvb, offset));
  }
  return static_cast<guint>(kMbapCarrierBytes + length);
}

int dissect_mbap(tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree, void* data) {
  tcp_dissect_pdus(tvb, pinfo, tree, TRUE, kMbapHeaderBytes, adu_length, dissect_adu, data);
  return static_cast<int>(tvb_captured_length(tvb));
}

}  // namespace

void register_mbap_protocol() {
  g_mbap.proto = proto_register_protocol("pvtap Modbus/TCP (MBAP, frames read by invrtu)",
                                         "invMBAP", "invmbap");
  FieldList fields;
  fields.add(&g_mbap.transaction, "Transaction identifier", "invmbap.transaction", FT_UINT16,
             BASE_DEC);
  fields.add(&g_mbap.protocol_id, "Protocol identifier", "invmbap.protocol", FT_UINT16, BASE_DEC);
  fields.add(&g_mbap.length, "Length", "invmbap.length", FT_UINT16, BASE_DEC);
  fields.add(&g_mbap.unit, "Unit identifier", "invmbap.unit", FT_UINT8, BASE_DEC);
  fields.register_all(g_mbap.proto);
  static int* ett[] = {&g_mbap.ett};
  proto_register_subtree_array(ett, 1);
  ExpertList experts;
  experts.add(&g_mbap.bad_header, "invmbap.bad_header", PI_MALFORMED, PI_ERROR,
              "MBAP header that lied");
  experts.register_all(g_mbap.proto);
  g_mbap.handle = register_dissector("invmbap", dissect_mbap, g_mbap.proto);
  register_cleanup_routine(release_mbap_tracks);
}

void register_mbap_handoff() {
  dissector_add_uint_range_with_preference("tcp.port", "", g_mbap.handle);
}

}  // namespace pvtap::dissector
