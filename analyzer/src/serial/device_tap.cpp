#include "serial/device_tap.h"

#include <utility>

namespace pvtap::analyzer {
namespace {

std::string line_text(std::uint32_t baud, SerialLine line) {
  return std::to_string(baud) + " 8" + line.parity + std::to_string(line.stop_bits);
}

}  // namespace

DeviceTap::DeviceTap(std::string path, std::uint32_t baud, SerialLine line, bool search)
    : path_(std::move(path)), baud_(baud), line_(line) {
  if (search) {
    search_ = std::make_unique<AutoBaud>();
    baud_ = search_->baud();
    line_ = search_->line();
  }
  report_.path = path_;
  report_.line = line_text(baud_, line_);
}

bool DeviceTap::follow_search() {
  baud_ = search_->baud();
  line_ = search_->line();
  if (!port_.is_open()) return true;  // a reopening sets it
  if (port_.set_line(baud_, line_)) return true;
  report_.last_error = port_.error();
  return false;
}

bool DeviceTap::open() {
  if (!port_.open(path_, baud_, line_, search_ != nullptr)) {
    report_.last_error = port_.error();
    return false;
  }
  latency_ = lower_latency_timer(path_);
  if (!line_errors_.start(port_.line_errors())) report_.line_errors_note = port_.error();
  return true;
}

void DeviceTap::count_read(std::size_t bytes) {
  ++report_.reads;
  report_.bytes += bytes;
}

void DeviceTap::went_away(double now) {
  report_.last_error = port_.error();
  line_errors_.close();
  port_.close();
  ++report_.outages;
  outage_.begin(now);
}

bool DeviceTap::try_reopen(double now) {
  if (open()) {
    report_.outage_seconds += outage_.end(now);
    return true;
  }
  outage_.retry_later(now);
  return false;
}

void DeviceTap::sample_line_errors() {
  if (!port_.is_open() || !line_errors_.counting()) return;
  line_errors_.sample(port_.line_errors());
}

DeviceReport DeviceTap::report(double now) {
  DeviceReport r = report_;
  if (search_) {
    r.line = search_->settled() ? search_->setting_text() + " (found from the traffic)"
                                : "not found (last tried " + search_->setting_text() + ")";
    r.found_line = search_->report(path_);
  }
  r.adapter = latency_.adapter;
  r.latency_timer_ms = latency_.ms;
  r.latency_note = latency_.note;
  sample_line_errors();
  r.line_errors = line_errors_.total();
  if (outage_.ongoing()) {
    r.lost_at_end = true;
    r.outage_seconds += now - outage_.since();
  }
  return r;
}

}  // namespace pvtap::analyzer
