// AuditRun: one `pvtap audit`: reads the inputs, feeds one bus session per bus, writes what
// the sessions report and, at the end, the summary. The protocol work is all in the core.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "audit_options.h"
#include "audit_report.h"
#include "pvtap/capture/capture_file.h"
#include "event_writer.h"
#include "pvtap/capture/exported_pdu_writer.h"
#include "gateway_traffic.h"
#include "pvtap/capture/link_types.h"
#include "output_stream.h"
#include "progress_bar.h"
#include "pvtap/bus_session.h"
#include "pvtap/distribution_summary.h"
#include "status_line.h"

namespace pvtap::analyzer {

// Exit statuses of pvtap audit.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFindings = 1;  // only with --fail-on errors
inline constexpr int kExitBadInput = 2;  // usage errors and unreadable input

// A one-line reason why an input cannot be audited (missing, not a capture, unsupported link
// type), checked for all inputs before any output is written; nullopt when all are fine.
std::optional<std::string> check_inputs(const AuditOptions& options);

class AuditRun : public BusDirectory {
 public:
  AuditRun(const AuditOptions& options, const RegisterDecoder& decoder, OutputStream& out);
  ~AuditRun() override;

  // Runs the whole audit; returns the exit status. Errors go to stderr as one line each.
  int run();

  BusSession& gateway_bus(const Endpoint& slave_side) override;

 private:
  class BusOutput;
  struct Bus;

  // Reading.
  bool open_outputs();
  bool read_inputs();  // false when an input ended early (truncated)
  void report_truncation() const;
  bool read_capture(const std::string& path, std::uint64_t done_before);
  bool read_raw(const std::string& path, std::uint64_t done_before);
  // Live capture (pvtap sniff), until a stop signal, --duration or --count; false when a
  // source could not be opened at the start.
  bool read_devices();         // device_reading.cpp
  bool read_live_interface();  // interface_reading.cpp
  // Shared by both (live_reading.cpp).
  bool count_reached() const;  // --count frames seen
  bool live_should_stop(double started) const;
  void flush_live_output(double now);
  void show_status(double now);
  void end_live_capture(double started, double now);
  // Network interface (interface_reading.cpp).
  void after_live_wake(double now);
  // Serial taps (device_reading.cpp).
  struct LiveTap;
  using LiveTaps = std::vector<std::unique_ptr<LiveTap>>;
  bool open_taps(LiveTaps& taps);
  BusSessionOptions tap_session_options(LiveTap& tap) const;
  void wait_for_taps(LiveTaps& taps, double wake_at);
  void read_tap(LiveTap& tap, std::span<std::uint8_t> buffer);
  void lose_tap(LiveTap& tap, double now);
  void revive_taps(LiveTaps& taps, double now);
  double next_wake(const LiveTaps& taps, double now, double started) const;
  void after_wake(LiveTaps& taps, double now);
  void on_record(InputKind kind, const CapturedPacket& packet);
  void on_network_packet(const CapturedPacket& packet);
  void on_exported_pdu(const CapturedPacket& packet);
  void feed_directed(BusSession& bus, Direction d, std::span<const std::uint8_t> bytes,
                     double time);

  // Buses and events.
  Bus& bus_named(const std::string& name, InputKind kind);
  Bus& add_bus(const std::string& name, const BusSessionOptions& options);
  BusSession& serial_bus(InputKind kind);
  BusSessionOptions session_options(InputKind kind) const;
  void on_frame(const EventContext& c, const SessionFrame& f);
  void on_noise(const EventContext& c, const SessionNoise& n);
  void finish_all(double time);

  // Results.
  AuditReport build_report() const;
  void write_summary(const AuditReport& report);
  bool has_findings(const AuditReport& report) const;

  const AuditOptions& options_;
  const RegisterDecoder& decoder_;
  OutputStream& out_;
  std::unique_ptr<EventWriter> events_;
  std::optional<ExportedPduWriter> writer_;
  std::unique_ptr<ProgressBar> progress_;
  GatewayTraffic gateway_;
  std::vector<std::unique_ptr<Bus>> buses_;
  std::map<std::string, Bus*> bus_by_name_;
  int link_type_ = -1;
  double last_time_ = 0;
  std::vector<InputReport> inputs_;
  SkippedRecords skipped_;
  DistributionAccumulator latency_;
  bool network_ = false;
  LiveSources live_;
  // For --count and the live status line.
  std::uint64_t frames_seen_ = 0;
  std::uint64_t timeouts_seen_ = 0;
  std::optional<double> last_latency_;
  std::unique_ptr<StatusLine> status_;
  // USER0-15 records of several bytes are read() chunks, stamped when the read returned.
  bool batched_serial_records_ = false;
};

}  // namespace pvtap::analyzer
