// EventLines: the jsonl writer rendering into a buffer that is emptied line by line.
#include "mqtt/event_lines.h"

#include "writers/event_writers.h"

namespace pvtap::analyzer {

EventLines::EventLines()
    : sink_(std::fopen("/dev/null", "w")),
      stream_(std::make_unique<OutputStream>(sink_)),
      jsonl_(make_jsonl_event_writer(*stream_)) {}

EventLines::~EventLines() {
  jsonl_.reset();
  stream_.reset();
  if (sink_ != nullptr) std::fclose(sink_);
}

std::string EventLines::frame(const EventContext& c, const SessionFrame& f) {
  jsonl_->frame(c, f);
  return take();
}

std::string EventLines::timeout(const EventContext& c, const SessionTimeout& t) {
  jsonl_->timeout(c, t);
  return take();
}

std::string EventLines::gap(const EventContext& c, const SessionGap& g) {
  jsonl_->gap(c, g);
  return take();
}

std::string EventLines::take() {
  std::string& buffer = stream_->buffer();
  if (!buffer.empty() && buffer.back() == '\n') buffer.pop_back();
  std::string line = buffer;  // a copy: the buffer keeps its capacity for the next line
  buffer.clear();
  return line;
}

}  // namespace pvtap::analyzer
