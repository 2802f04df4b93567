// StationTally: the per-station counters of a BusReport, each frame and finding counted under
// the station the station rule gives it (pvtap/session/station_rule.h), or the unknown station.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>

#include "pvtap/session/bus_report.h"
#include "pvtap/session/bus_session.h"

namespace pvtap::detail {

class StationTally {
 public:
  void add_frame(const SessionFrame& f);
  void add_transaction(const Transaction& t);
  void add_timeout(const SessionTimeout& t);
  // The stations that exist and the unknown station. A damaged request still waiting for its
  // reply or its timeout is in neither yet.
  void fill(BusReport& r) const;

 private:
  StationSummary& station(std::uint8_t s);
  void count_frame(StationSummary& s, const SessionFrame& f);
  void count_request(std::optional<std::uint8_t> owner, std::uint8_t claimed, Dialect d);
  void count_unknown(std::uint8_t claimed);

  // Made when a station is first counted: a bus has a few stations of 256, and a session is
  // made per bus (and per input by the fuzz targets), so 256 summaries are not zeroed up front.
  std::array<std::unique_ptr<StationSummary>, 256> stations_{};
  std::array<std::uint64_t, 256> claimed_{};  // damaged frames of no station, by the address
  std::uint64_t unknown_frames_ = 0;
  std::uint64_t unknown_unanswered_ = 0;
  // A damaged broadcast request answered by several stations is counted once.
  std::optional<std::uint64_t> last_settled_request_;
};

}  // namespace pvtap::detail
