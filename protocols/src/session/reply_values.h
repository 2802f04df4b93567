// ReplyValues: what a session keeps to give frames their values: the last request of each
// station (a reply's words are placed by it, a timeout reports its times), the newest readings
// of each station, and the values decoded for the frame being handled.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "matching/request_book.h"
#include "pvtap/session/bus_session.h"
#include "session/latest_readings.h"

namespace pvtap::detail {

class ReplyValues {
 public:
  ReplyValues(const RegisterDecoder& decoder, const BusSessionOptions& options)
      : decoder_(decoder),
        has_timestamps_(options.has_timestamps),
        decode_values_(options.decode_values),
        latest_(decoder, options.infer_registers) {}

  void remember_request(const SessionFrame& out, const Frame& request) {
    requests_.remember(out.id, request, out.start_time, out.end_time, out.check.ok);
  }
  // The request a timeout gave up, while it is still the last of its slot.
  const RequestRecord* waiting_request(const Timeout& t) const {
    return requests_.find(RequestBook::slot_of(t.dialect, t.station), t.request_id);
  }
  // Fills in what `frame` answers (request, latency, where its words belong), whether its
  // values can be trusted, and its values; keeps a sound reply as its station's newest data.
  void take(SessionFrame& out, const Frame& frame, const FrameMatch& match);
  // The newest values of every station, decoded now.
  std::map<std::uint8_t, StationReadings> latest() const { return latest_.decode(decoder_); }
  // The inferred blocks of every station.
  std::map<std::uint8_t, std::vector<InferredBlock>> inferred() const { return latest_.inferred(); }

 private:
  const RequestRecord* answered_request(SessionFrame& out, const FrameMatch& match) const;
  void decode(SessionFrame& out, const Frame& frame, const Frame* request);

  const RegisterDecoder& decoder_;
  bool has_timestamps_;
  bool decode_values_;
  RequestBook requests_;
  LatestReadings latest_;
  std::vector<DecodedValue> values_;  // SessionFrame::values points here
};

}  // namespace pvtap::detail
