#include "stream/call_view.h"

#include <epan/proto_data.h>

#include <algorithm>
#include <vector>

#include "stream/piece_display.h"

namespace pvtap::dissector {
namespace {

// The timeouts not announced yet. noexcept: nothing may be thrown into Wireshark.
std::vector<FrameRecord*> unannounced(TimeoutQueue& queue) noexcept {
  try {
    return queue.take_shown();
  } catch (...) {
    return {};  // out of memory: a later call announces them
  }
}

}  // namespace

FrameRecord** announce_timeouts(packet_info* pinfo, TimeoutQueue& queue, std::uint32_t& count) {
  const std::vector<FrameRecord*> ready = unannounced(queue);
  count = static_cast<std::uint32_t>(ready.size());
  if (ready.empty()) return nullptr;
  auto** requests = wmem_alloc_array(wmem_file_scope(), FrameRecord*, ready.size());
  for (std::size_t i = 0; i < ready.size(); ++i) {
    requests[i] = ready[i];
    ready[i]->announced_in = pinfo->num;
  }
  return requests;
}

// The collisions the session named, copied into file scope for later passes and taken.
SessionCollision* announce_collisions(std::vector<SessionCollision>& named, std::uint32_t& count) {
  count = static_cast<std::uint32_t>(named.size());
  if (named.empty()) return nullptr;
  auto* out = wmem_alloc_array(wmem_file_scope(), SessionCollision, named.size());
  std::copy(named.begin(), named.end(), out);
  named.clear();
  return out;
}

void note_timeouts(CallView& view, packet_info* pinfo, BusTrack& bus) {
  if (PINFO_FD_VISITED(pinfo) || view.extends_pdu) return;
  view.timeouts = announce_timeouts(pinfo, bus.timeouts(), view.timeout_count);
  view.collisions = announce_collisions(bus.collisions(), view.collision_count);
}

CallView* noted_view(packet_info* pinfo, int proto, guint32 number) {
  return static_cast<CallView*>(p_get_proto_data(wmem_file_scope(), pinfo, proto, number));
}

CallView& note_view(packet_info* pinfo, int proto, guint32 number) {
  auto* view = new (wmem_alloc(wmem_file_scope(), sizeof(CallView))) CallView{};
  p_add_proto_data(wmem_file_scope(), pinfo, proto, number, view);
  return *view;
}

void show_timeouts(const CallView& view, tvbuff_t* tvb, packet_info* pinfo, proto_tree* tree) {
  for (std::uint32_t i = 0; i < view.timeout_count; ++i) {
    show_timeout(*view.timeouts[i], tvb, pinfo, tree);
  }
  for (std::uint32_t i = 0; i < view.collision_count; ++i) {
    show_collision(view.collisions[i], tvb, pinfo, tree);
  }
}

}  // namespace pvtap::dissector
