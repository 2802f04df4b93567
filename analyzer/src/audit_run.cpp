#include "audit_run.h"

#include "audit_bus.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "summary_writers.h"

namespace pvtap::analyzer {
namespace {

constexpr std::size_t kRawChunk = 64 * 1024;
// Progress is checked every this many records: a clock read per packet would cost too much.
constexpr std::uint64_t kProgressEvery = 4096;
// Records looked at to tell per-character timestamps (one byte per record) from read chunks.
constexpr std::size_t kTimingProbeRecords = 64;

std::optional<std::string> check_raw_dump(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return path + ": " + std::strerror(errno);
  if (S_ISDIR(st.st_mode)) return path + ": is a directory";
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return path + ": " + std::strerror(errno);
  std::fclose(f);
  return std::nullopt;
}

std::uint64_t file_size(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 ? static_cast<std::uint64_t>(st.st_size) : 0;
}

std::unique_ptr<EventWriter> make_event_writer(OutputFormat format, OutputStream& out) {
  switch (format) {
    case OutputFormat::Jsonl:
      return make_jsonl_event_writer(out);
    case OutputFormat::Csv:
      return make_csv_event_writer(out);
    case OutputFormat::Text:
      break;
  }
  return make_text_event_writer(out);
}

}  // namespace

std::optional<std::string> check_inputs(const AuditOptions& options) {
  for (const std::string& path : options.captures) {
    CaptureFile file;
    if (!file.open(path)) return path + ": " + file.error();
    if (!input_kind_of(file.link_type())) {
      return path + ": unsupported link type " + file.link_type_name() +
             "; supported: " + supported_link_types_text();
    }
  }
  for (const std::string& path : options.raw_dumps) {
    if (auto error = check_raw_dump(path)) return error;
  }
  return std::nullopt;
}

AuditRun::AuditRun(const AuditOptions& options, const RegisterDecoder& decoder, OutputStream& out)
    : options_(options),
      decoder_(decoder),
      out_(out),
      gateway_(GatewayOptions{options.ports, options.dialects, 2.0}, *this) {}

AuditRun::~AuditRun() = default;

bool AuditRun::open_outputs() {
  if (!options_.write_path.empty()) {
    writer_.emplace();
    if (!writer_->open(options_.write_path)) {
      std::fprintf(stderr, "pvtap: cannot write %s: %s\n", options_.write_path.c_str(),
                   writer_->error().c_str());
      return false;
    }
    writer_->flush_each_record(options_.live.flush_each_record);
  }
  // Before any output line (a csv header): a broker that refuses is an error with no output.
  if (!open_mqtt()) return false;
  if (!options_.summary_only) {
    events_ = make_event_writer(options_.format, out_);
    events_->begin();
  }
  return true;
}

bool AuditRun::open_mqtt() {
  if (!options_.mqtt.active()) return true;
  std::string error;
  mqtt_ = MqttPublisher::open(options_.mqtt, options_.live.active(), error);
  if (!mqtt_) std::fprintf(stderr, "pvtap: %s\n", error.c_str());
  return mqtt_ != nullptr;
}

bool AuditRun::read_inputs() {
  if (!options_.live.devices.empty()) return read_devices();
  if (!options_.live.interface.empty()) return read_live_interface();
  std::uint64_t total = 0;
  for (const auto& path : options_.captures) total += file_size(path);
  for (const auto& path : options_.raw_dumps) total += file_size(path);
  progress_ = std::make_unique<ProgressBar>(options_.progress, total);
  std::uint64_t done = 0;
  for (const auto& path : options_.captures) {
    // A truncated file ends the capture: what follows it would not join up.
    if (!read_capture(path, done)) return false;
    done += file_size(path);
  }
  bool complete = true;
  for (const auto& path : options_.raw_dumps) {
    complete = read_raw(path, done) && complete;
    done += file_size(path);
  }
  return complete;
}

void AuditRun::report_truncation() const {
  const InputReport& in = inputs_.back();
  std::fprintf(stderr,
               "pvtap: %s: truncated capture: %s (read %llu records, %llu of %llu bytes; "
               "results up to there are above)\n",
               in.path.c_str(), in.error.c_str(), static_cast<unsigned long long>(in.records),
               static_cast<unsigned long long>(in.read_bytes),
               static_cast<unsigned long long>(in.file_bytes));
}

int AuditRun::run() {
  if (!open_outputs()) return kExitBadInput;
  const bool complete = read_inputs();
  // A live source that could not be opened at the start: the reason is printed, nothing ran.
  if (!complete && options_.live.active()) return kExitBadInput;
  finish_all(last_time_);
  if (mqtt_) mqtt_->finish(last_time_);
  if (progress_) progress_->clear();
  const AuditReport report = build_report();
  write_summary(report);
  out_.flush();
  if (writer_ && !writer_->close()) {
    std::fprintf(stderr, "pvtap: cannot write %s: %s\n", options_.write_path.c_str(),
                 writer_->error().c_str());
    return kExitBadInput;
  }
  if (!complete) {
    report_truncation();
    return kExitBadInput;
  }
  return options_.fail_on_errors && has_findings(report) ? kExitFindings : kExitOk;
}

bool AuditRun::read_capture(const std::string& path, std::uint64_t done_before) {
  CaptureFile file;
  InputReport in;
  in.path = path;
  if (!file.open(path)) {
    in.truncated = true;
    in.error = file.error();
    inputs_.push_back(in);
    return false;
  }
  in.link_type = file.link_type_name();
  const InputKind kind = *input_kind_of(file.link_type());
  link_type_ = file.link_type();
  if (kind == InputKind::Serial && bus_by_name_.count("") == 0) {
    batched_serial_records_ = largest_early_record(path, kTimingProbeRecords) > 1;
  }
  network_ = network_ || kind == InputKind::Network;
  CapturedPacket packet;
  for (;;) {
    const CaptureFile::Next next = file.next(packet);
    if (next == CaptureFile::Next::End) break;
    if (next == CaptureFile::Next::Truncated) {
      in.truncated = true;
      in.error = file.error();
      break;
    }
    last_time_ = std::max(last_time_, packet.time);
    on_record(kind, packet);
    if (file.packets() % kProgressEvery == 0) progress_->update(done_before + file.position());
  }
  in.records = file.packets();
  in.file_bytes = file.size();
  in.read_bytes = in.truncated ? file.position() : file.size();
  inputs_.push_back(in);
  return !in.truncated;
}

bool AuditRun::read_raw(const std::string& path, std::uint64_t done_before) {
  InputReport in;
  in.path = path;
  in.link_type = "plain bus bytes";
  in.file_bytes = file_size(path);
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    in.truncated = true;
    in.error = std::strerror(errno);
    inputs_.push_back(in);
    return false;
  }
  std::vector<std::uint8_t> chunk(kRawChunk);
  BusSession& bus = serial_bus(InputKind::Serial);
  for (;;) {
    const std::size_t n = std::fread(chunk.data(), 1, chunk.size(), f);
    if (n == 0) break;
    ++in.records;
    in.read_bytes += n;
    bus.feed(BusChunk{std::span(chunk).first(n), 0.0, Direction::Unknown});
    progress_->update(done_before + in.read_bytes);
  }
  if (std::ferror(f) != 0) {
    in.truncated = true;
    in.error = "read error";
  }
  std::fclose(f);
  inputs_.push_back(in);
  return !in.truncated;
}

void AuditRun::write_summary(const AuditReport& report) {
  switch (options_.format) {
    case OutputFormat::Jsonl:
      write_json_summary(report, out_);
      return;
    case OutputFormat::Csv:
      // A CSV file holds rows of one shape; the report is only written when asked for alone.
      if (options_.summary_only) write_text_report(report, out_);
      return;
    case OutputFormat::Text:
      write_text_report(report, out_);
      return;
  }
}

}  // namespace pvtap::analyzer
