// RequestBook: the last request seen for each station (and the Hybrid broadcast), kept whole
// so that a reply can be decoded against it and a timeout reported with its times.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>

#include "dialects/dialect_module.h"
#include "pvtap/codec/frame.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {

// RequestRecord: one remembered request.
struct RequestRecord {
  std::uint64_t id = 0;
  bool valid = false;
  bool check_ok = true;
  double start_time = 0;
  double end_time = 0;
  Frame frame;
};

class RequestBook {
 public:
  static constexpr std::size_t kBroadcastSlot = 256;

  // The slot the matcher keeps for requests like this one: the broadcast has its own.
  static std::size_t slot_of(Dialect d, std::uint8_t station) {
    return detail::answered_broadcast(d, station) ? kBroadcastSlot : station;
  }

  void remember(std::uint64_t id, const Frame& frame, double start, double end, bool check_ok) {
    std::unique_ptr<RequestRecord>& slot = slots_[slot_of(frame.dialect, frame.station)];
    if (!slot) slot = std::make_unique<RequestRecord>();
    RequestRecord& r = *slot;
    r.id = id;
    r.valid = true;
    r.check_ok = check_ok;
    r.start_time = start;
    r.end_time = end;
    r.frame = frame;
  }

  // The request with this id if it is still the last one of its slot.
  const RequestRecord* find(std::size_t slot, std::uint64_t id) const {
    const RequestRecord* r = slots_[slot].get();
    return r != nullptr && r->valid && r->id == id ? r : nullptr;
  }

 private:
  // Made when a station's first request is remembered: a record is 864 bytes, and a session
  // (one per bus, and one per input in the fuzz targets) would otherwise zero 222 KB up front.
  std::array<std::unique_ptr<RequestRecord>, 257> slots_{};
};

}  // namespace pvtap::detail
