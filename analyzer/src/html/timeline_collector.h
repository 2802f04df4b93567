// TimelineCollector: an EventWriter that keeps what the HTML report draws over time (see
// timeline.h), in memory bounded by stations, registers and buckets, not by the input's length.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>

#include "events/event_writer.h"
#include "html/timeline.h"

namespace pvtap::analyzer {

class TimelineCollector : public EventWriter {
 public:
  void frame(const EventContext& c, const SessionFrame& f) override;
  void timeout(const EventContext& c, const SessionTimeout& t) override;
  void noise(const EventContext& c, const SessionNoise& n) override;
  void gap(const EventContext& c, const SessionGap& g) override;
  void collision(const EventContext& c, const SessionCollision& k) override;

  // The timeline so far, moved out (call once, at the end).
  Timeline finish();

 private:
  struct BusState {
    std::string name;
    std::uint32_t bus_lane = 0;
    std::uint32_t load = 0;
    std::map<std::uint8_t, std::uint32_t> station_lanes;
    std::optional<double> last_request;
  };
  struct SeriesKey {
    std::uint32_t lane;
    const RegisterDef* def;  // null: a word no map names, at `instance` of `table`
    std::uint16_t instance;
    RegisterTable table;
    bool operator==(const SeriesKey&) const = default;
  };
  struct SeriesKeyHash {
    std::size_t operator()(const SeriesKey& k) const {
      return std::hash<const void*>{}(k.def) ^ (std::size_t{k.lane} << 20) ^ k.instance ^
             (std::size_t{static_cast<std::uint8_t>(k.table)} << 16);
    }
  };

  BusState& bus_of(const EventContext& c);
  std::uint32_t station_lane(BusState& bus, std::uint8_t station);
  std::uint32_t lane_of(BusState& bus, const SessionFrame& f);
  std::uint32_t known_lane(const BusState& bus, std::uint8_t station) const;
  std::size_t bucket_of(double time);
  void add_mark(Mark mark);
  void count_frame(BusState& bus, std::uint32_t lane, std::size_t bucket, const SessionFrame& f);
  void mark_frame(std::uint32_t lane, const SessionFrame& f);
  void add_values(std::uint32_t lane, std::size_t bucket, const SessionFrame& f);
  void note_request(BusState& bus, double time);

  // The blocks of recent requests by frame id, so that a timeout's tooltip can name the block
  // its request asked for (a request is given up within the timeout, long before 64 more).
  struct RequestBlock {
    std::uint64_t id = ~std::uint64_t{0};
    const void* bus = nullptr;
    std::optional<std::uint16_t> start, count;
  };
  std::array<RequestBlock, 64> recent_requests_{};

  Timeline timeline_;
  TimeGrid grid_;
  std::map<std::string, BusState, std::less<>> buses_;
  // The bus of the previous event: events come in runs of one bus, whose name stays put.
  const char* last_bus_name_ = nullptr;
  BusState* last_bus_ = nullptr;
  std::unordered_map<SeriesKey, std::uint32_t, SeriesKeyHash> series_;
  std::array<std::size_t, kMarkKinds> marks_kept_{};
};

}  // namespace pvtap::analyzer
