// EventLines: an event as its --format jsonl line, the payload of PREFIX/<bus>/events.
#pragma once

#include <cstdio>
#include <memory>
#include <string>

#include "events/event_writer.h"
#include "formatting/output_stream.h"

namespace pvtap::analyzer {

// The jsonl writer renders into its stream's buffer, from which each line is taken at once:
// one line never reaches the flush size, so nothing is ever written to the sink.
class EventLines {
 public:
  EventLines();
  ~EventLines();
  EventLines(const EventLines&) = delete;
  EventLines& operator=(const EventLines&) = delete;

  // The event's line, without its newline.
  std::string frame(const EventContext& c, const SessionFrame& f);
  std::string timeout(const EventContext& c, const SessionTimeout& t);
  std::string gap(const EventContext& c, const SessionGap& g);

 private:
  std::string take();

  std::FILE* sink_ = nullptr;
  std::unique_ptr<OutputStream> stream_;
  std::unique_ptr<EventWriter> jsonl_;
};

}  // namespace pvtap::analyzer
