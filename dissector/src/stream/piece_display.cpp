#include "stream/piece_display.h"

#include <epan/proto_data.h>

#include "plan/frame_analysis.h"
#include "pvtap/codec/noise_resemblance.h"
#include "settings/register_decoding.h"
#include "statistics/response_time_stats.h"
#include "tree/frame_tree.h"

namespace pvtap::dissector {
namespace {

// PacketCounters: how many pieces of a protocol this packet showed so far, and how many times
// the bound protocol was called for it (TCP may call more than once per packet).
struct PacketCounters {
  guint pieces = 0;
  guint calls = 0;
};

constexpr guint32 kCountersKey = 0;

PacketCounters& counters_of(packet_info* pinfo, int proto) {
  auto* c = static_cast<PacketCounters*>(p_get_proto_data(pinfo->pool, pinfo, proto, kCountersKey));
  if (c == nullptr) {
    c = new (wmem_alloc(pinfo->pool, sizeof(PacketCounters))) PacketCounters{};
    p_add_proto_data(pinfo->pool, pinfo, proto, kCountersKey, c);
  }
  return *c;
}

void add_info(packet_info* pinfo, const InverterProtocol& p, const char* text) {
  PacketCounters& c = counters_of(pinfo, p.proto);
  if (c.pieces++ == 0) {
    col_set_str(pinfo->cinfo, COL_PROTOCOL, p.short_name);
    col_clear(pinfo->cinfo, COL_INFO);
    col_add_str(pinfo->cinfo, COL_INFO, text);
  } else {
    col_append_sep_str(pinfo->cinfo, COL_INFO, " | ", text);
  }
}

// The Info column's text of a frame: its summary, and what its reply was when it was a second.
const char* info_summary(packet_info* pinfo, const FrameRecord& record, const char* summary) {
  if (record.duplicate) return wmem_strdup_printf(pinfo->pool, "%s (duplicate)", summary);
  if (record.address_conflict) {
    return wmem_strdup_printf(pinfo->pool, "%s (address conflict)", summary);
  }
  if (record.echo) return wmem_strdup_printf(pinfo->pool, "%s (echo)", summary);
  return summary;
}

// The packet's pool: freed with the packet, without destructors.
Arena packet_arena(packet_info* pinfo) {
  constexpr auto allocate = [](void* pool, std::size_t size) {
    return wmem_alloc(static_cast<wmem_allocator_t*>(pool), size);
  };
  return Arena{allocate, pinfo->pool};
}

void dissect_frame(const TreeTarget& target, std::span<const std::uint8_t> bytes,
                   FrameRecord& record) {
  // The first packet to show a frame is the one its links point to.
  if (record.packet == 0) {
    record.packet = target.pinfo->num;
    record.time = {target.pinfo->abs_ts.secs, target.pinfo->abs_ts.nsecs};
  }
  const InverterProtocol& p = *target.protocol;
  AnalysisContext actx;
  actx.decoder = &register_decoder();
  actx.record = &record;
  actx.arena = packet_arena(target.pinfo);
  actx.check_word = p.check_word;
  actx.verify_check = p.settings.verify_check;
  actx.with_values = target.tree != nullptr;
  FramePlan plan;
  analyze_frame(bytes, actx, plan);
  const DescriptionContext dctx{.arena = actx.arena,
                                .length = target.length,
                                .visited = PINFO_FD_VISITED(target.pinfo) != 0,
                                .check_word = p.check_word,
                                .reply_timeout_ms = p.settings.reply_timeout_ms};
  const TreeDescription tree = describe_frame(plan, record, dctx);
  // Only now the calls that may longjmp: the plan and the tree's description are plain data.
  add_info(target.pinfo, p, info_summary(target.pinfo, record, plan.summary));
  queue_response_time(target.pinfo, p, record);
  add_tree(target, tree);
}

// Noise goes to the protocol whose frames it resembles: a damaged ASCII frame to invascii,
// anything else to the conversation's protocol. Only RTU noise can hold an RTU frame of an
// unknown function.
void dissect_noise(TreeTarget target, std::span<const std::uint8_t> bytes) {
  const auto unknown =
      target.protocol->dialects.rtu() ? unknown_function_frame(bytes) : std::nullopt;
  if (!unknown && resembles_ascii_frame(bytes)) target.protocol = &ascii_protocol();
  const char* text =
      unknown ? wmem_strdup_printf(target.pinfo->pool, "frame of unknown function code 0x%02X",
                                   unknown->function)
              : wmem_strdup_printf(target.pinfo->pool, "noise (%d bytes)", target.length);
  const TreeDescription tree =
      describe_noise(unknown, {.arena = packet_arena(target.pinfo), .length = target.length});
  add_info(target.pinfo, *target.protocol, text);
  add_tree(target, tree);
}

}  // namespace

void show_piece(const PieceTarget& t, const BusPiece& piece, std::span<const std::uint8_t> bytes,
                int offset) {
  FrameRecord* record = piece.frame ? t.bus->record(piece.frame_id) : nullptr;
  // A frame goes to the protocol of its dialect: one gateway may carry ASCII and RTU stations.
  InverterProtocol* protocol = record != nullptr ? &protocol_of(record->dialect) : t.bound;
  const TreeTarget target{t.tvb, t.pinfo, t.tree, offset, static_cast<int>(piece.length), protocol};
  if (record != nullptr) {
    dissect_frame(target, bytes, *record);
  } else {
    dissect_noise(target, bytes);
  }
}

void show_frame(const TreeTarget& target, std::span<const std::uint8_t> bytes,
                FrameRecord& record) {
  dissect_frame(target, bytes, record);
}

void show_noise(const TreeTarget& target, std::span<const std::uint8_t> bytes) {
  dissect_noise(target, bytes);
}

void show_timeout(const FrameRecord& request, tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree) {
  InverterProtocol& p = protocol_of(request.dialect);
  const DescriptionContext dctx{.arena = packet_arena(pinfo),
                                .visited = PINFO_FD_VISITED(pinfo) != 0,
                                .check_word = p.check_word,
                                .reply_timeout_ms = p.settings.reply_timeout_ms};
  const TreeDescription description = describe_timeout(request, dctx);
  add_info(pinfo, p, wmem_strdup_printf(pinfo->pool, "no reply to frame %u", request.packet));
  add_tree(TreeTarget{tvb, pinfo, tree, 0, 0, &p}, description);
}

void show_collision(const SessionCollision& collision, tvbuff_t* tvb, packet_info* pinfo,
                    proto_tree* tree) {
  InverterProtocol& p = rtu_protocol();
  add_info(pinfo, p, "collision");
  const double now = nstime_to_sec(&pinfo->abs_ts);
  proto_tree_add_expert_format(
      tree, pinfo, p.ei.of(TreeExpert::Collision), tvb, 0, 0,
      "Collision %.6f s before this packet: two transmissions at once garbled the bus for "
      "%.1f ms or more (a bus of more than one master)%s",
      now - collision.start_time, (collision.end_time - collision.start_time) * 1e3,
      collision.late ? "; named now that the bus showed its second master" : "");
}

guint32 next_call_number(packet_info* pinfo, int proto) {
  return 1 + counters_of(pinfo, proto).calls++;
}

}  // namespace pvtap::dissector
