// SerialTaps: pvtap sniff --device: RS485 taps opened read-only, each its own bus of the
// pipeline, or with --duplex two taps on the two pairs of one 4-wire bus. A poll loop stamps each
// read with the capture clock, tells the buses when they have been silent, and survives adapters
// that go away and come back.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "pipeline/pipeline.h"
#include "report/live_report.h"
#include "serial/auto_baud.h"
#include "sources/live_loop.h"
#include "sources/live_options.h"

namespace pvtap::analyzer {

// The one bus of a --duplex pair: "REQ+REP", as the devices were given.
std::string duplex_bus_name(const LiveOptions& live);

class SerialTaps {
 public:
  // The taps of `live`, whose bus runs at `baud`.
  SerialTaps(const LiveOptions& live, std::uint32_t baud, Pipeline& pipeline);
  ~SerialTaps();

  // Opens every device and adds its bus; false (after saying why) when one cannot be opened.
  bool open();
  // Reads until the loop says stop; the taps' reports go into `live`.
  void run(LiveLoop& loop, LiveSources& live);
  // --baud auto: the lines the taps' searches found, on the buses of `report`.
  static void add_found_lines(AuditReport& report);

 private:
  struct Tap;
  BusSessionOptions session_options(Tap& tap) const;
  void wait(double wake_at);
  void read(Tap& tap, std::span<std::uint8_t> buffer);
  BusSession& bus_of(Tap& tap);
  void searched_read(Tap& tap, std::span<const std::uint8_t> bytes, double time);
  void after_search(Tap& tap, const AutoBaud::Outcome& outcome, double now);
  void show_searches();
  void lose(Tap& tap, double now);
  void revive(double now);
  double next_wake(double now) const;
  void after_wake(double now);
  void report_line_errors(double now);
  void report_duplex_line_errors(double now);

  const LiveOptions& live_;
  std::uint32_t baud_;
  Pipeline& pipeline_;
  LiveLoop* loop_ = nullptr;  // while run() runs
  double next_sample_ = 0;    // when the line error counters are read next
  std::vector<std::unique_ptr<Tap>> taps_;
};

}  // namespace pvtap::analyzer
