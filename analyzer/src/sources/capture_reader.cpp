#include "sources/capture_reader.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>

#include "pvtap/pcap/read_ahead_capture.h"

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

unsigned long long u(std::uint64_t v) {
  return static_cast<unsigned long long>(v);
}

// The input line's word for a pair of a 4-wire bus (--duplex).
std::string pair_of(Direction direction) {
  switch (direction) {
    case Direction::ToSlave:
      return "requests";
    case Direction::FromSlave:
      return "replies";
    case Direction::Unknown:
      break;
  }
  return {};
}

}  // namespace

// Source: one file being read, holding its next record until that record's turn comes.
struct CaptureReader::Source {
  explicit Source(bool read_ahead) : file(read_ahead) {}
  ReadAheadCapture file;
  CapturedPacket packet;  // the next record; its time moved on by `offset`
  std::size_t slot = 0;   // its InputReport in inputs_
  bool batched = false;   // serial records that are read chunks (see Pipeline::begin_input)
  Direction direction = Direction::Unknown;  // of its serial records (PlannedCapture)
  double offset = 0;                         // what the file's clock stepped back by, so far
  double last_time = -std::numeric_limits<double>::infinity();  // of `packet`
};

std::optional<std::string> check_raw_dumps(const std::vector<std::string>& raw_dumps) {
  for (const std::string& path : raw_dumps) {
    if (auto error = check_raw_dump(path)) return error;
  }
  return std::nullopt;
}

std::uint64_t total_size(const std::vector<std::string>& captures,
                         const std::vector<std::string>& raw_dumps) {
  std::uint64_t total = 0;
  for (const auto& path : captures) total += file_size(path);
  for (const auto& path : raw_dumps) total += file_size(path);
  return total;
}

CaptureReader::CaptureReader(Pipeline& pipeline, ProgressBar& progress, bool read_ahead)
    : pipeline_(pipeline), progress_(progress), read_ahead_(read_ahead) {}

CaptureReader::~CaptureReader() = default;

bool CaptureReader::read(const CapturePlan& plan, const std::vector<std::string>& raw_dumps) {
  read_captures(plan);
  for (const PlannedCapture& planned : plan.unreadable) {
    InputReport in;
    in.path = planned.path;
    in.pair = pair_of(planned.direction);
    in.unreadable = true;
    in.error = planned.error;
    inputs_.push_back(in);
  }
  for (const auto& path : raw_dumps) read_raw(path);
  return !repeat_ && std::none_of(inputs_.begin(), inputs_.end(),
                                  [](const InputReport& in) { return in.damaged(); });
}

void CaptureReader::report_problems() const {
  for (const InputReport& in : inputs_) {
    if (in.truncated) {
      std::fprintf(stderr,
                   "pvtap: %s: damaged capture, %s (read %llu records, %llu of %llu bytes; "
                   "what it held up to there is kept)\n",
                   in.path.c_str(), in.error.c_str(), u(in.records), u(in.read_bytes),
                   u(in.file_bytes));
    } else if (in.unreadable) {
      std::fprintf(stderr, "pvtap: %s: %s; not read (the other inputs were)\n", in.path.c_str(),
                   in.error.c_str());
    }
  }
  if (repeat_) std::fprintf(stderr, "pvtap: %s\n", repeat_->c_str());
}

// One loop over every file's next record: the earliest goes first, and a file is opened
// when its first record's turn comes, so that files apart in time are read one at a time.
bool CaptureReader::read_captures(const CapturePlan& plan) {
  std::vector<std::unique_ptr<Source>> active;
  std::size_t next = 0;
  std::size_t fed_slot = inputs_.size() + plan.readable.size();  // none yet
  for (;;) {
    open_due(plan, next, active);
    if (active.empty()) break;
    auto earliest = active.begin();
    for (auto it = active.begin() + 1; it != active.end(); ++it) {
      if ((*it)->packet.time < (*earliest)->packet.time) earliest = it;
    }
    Source& source = **earliest;
    if (active.size() > 1) {
      repeat_ = repeat_of(source, active);
      if (repeat_) break;
    }
    if (source.slot != fed_slot) {
      pipeline_.begin_input(source.file.link_type(), source.batched, source.direction);
      fed_slot = source.slot;
    }
    // A file alone is fed up to the next file's first record without looking again.
    const double until =
        active.size() > 1 ? -std::numeric_limits<double>::infinity() : first_time_of(plan, next);
    if (!feed_until(source, until, active)) {
      close(source);
      active.erase(earliest);
    }
  }
  // After repeated records the run stops: what was not read is said so.
  for (const auto& source : active) {
    close(*source);
    InputReport& in = inputs_[source->slot];
    in.error = "reading stopped at the repeated records";
    in.read_bytes = 0;  // where the reading thread was is no fact of the capture
  }
  for (; next < plan.readable.size(); ++next) {
    InputReport in;
    in.path = plan.readable[next].path;
    in.unreadable = true;
    in.error = "the audit stopped at the repeated records";
    inputs_.push_back(in);
  }
  return !repeat_;
}

// The source's records, at least one, while they come before `until`; false at its end.
bool CaptureReader::feed_until(Source& source, double until,
                               const std::vector<std::unique_ptr<Source>>& active) {
  do {
    pipeline_.record(source.packet);
    if (++fed_ % kProgressEvery == 0) {
      std::uint64_t position = done_bytes_;
      for (const auto& s : active) position += s->file.position();
      progress_.update(position);
    }
    if (!advance(source)) return false;
  } while (source.packet.time < until);
  return true;
}

double CaptureReader::first_time_of(const CapturePlan& plan, std::size_t next) {
  if (next < plan.readable.size() && plan.readable[next].first_time) {
    return *plan.readable[next].first_time;
  }
  return std::numeric_limits<double>::infinity();
}

void CaptureReader::open_due(const CapturePlan& plan, std::size_t& next,
                             std::vector<std::unique_ptr<Source>>& active) {
  while (next < plan.readable.size()) {
    const PlannedCapture& planned = plan.readable[next];
    if (!active.empty()) {
      double head = active.front()->packet.time;
      for (const auto& s : active) head = std::min(head, s->packet.time);
      if (!planned.first_time || *planned.first_time > head) return;
    }
    ++next;
    open(planned, active);
  }
}

void CaptureReader::open(const PlannedCapture& planned,
                         std::vector<std::unique_ptr<Source>>& active) {
  auto source = std::make_unique<Source>(read_ahead_);
  InputReport in;
  in.path = planned.path;
  in.pair = pair_of(planned.direction);
  if (!source->file.open(planned.path)) {
    in.unreadable = true;
    in.error = source->file.error();
    inputs_.push_back(in);
    return;
  }
  in.link_type = source->file.link_type_name();
  // Reading ahead to tell read chunks from characters costs a second open of the file: only
  // the input that decides the serial bus's timing is probed.
  const bool probe = input_kind_of(source->file.link_type()) == InputKind::Serial &&
                     pipeline_.serial_timing_open();
  source->batched = probe && largest_early_record(planned.path, kTimingProbeRecords) > 1;
  source->direction = planned.direction;
  source->slot = inputs_.size();
  inputs_.push_back(in);
  if (advance(*source)) {
    inputs_[source->slot].first_time = source->packet.time;
    active.push_back(std::move(source));
  } else {
    close(*source);
  }
}

// The source's next record; false at its end. A record earlier than the one before it in
// the same file is a step back of the file's clock: counted, and closed up.
bool CaptureReader::advance(Source& source) {
  const CaptureFile::Next next = source.file.next(source.packet);
  if (next != CaptureFile::Next::Packet) [[unlikely]] {
    return ended(source, next);
  }
  double time = source.packet.time + source.offset;
  if (time < source.last_time) [[unlikely]]
    time = step_back(source, time);
  source.packet.time = time;
  source.last_time = time;
  return true;
}

// Out of advance()'s way, so that its common path stays short.
bool CaptureReader::ended(Source& source, CaptureFile::Next next) {
  if (next == CaptureFile::Next::Truncated) {
    inputs_[source.slot].truncated = true;
    inputs_[source.slot].error = source.file.error();
  }
  return false;
}

double CaptureReader::step_back(Source& source, double time) {
  const double step = source.last_time - time;
  source.offset += step;
  InputReport& in = inputs_[source.slot];
  if (in.steps_back++ == 0) in.first_step_back_record = source.file.packets();
  in.largest_step_back = std::max(in.largest_step_back, step);
  return source.last_time;
}

void CaptureReader::close(Source& source) {
  InputReport& in = inputs_[source.slot];
  in.records = source.file.packets();
  in.file_bytes = source.file.size();
  in.read_bytes = in.truncated ? source.file.position() : source.file.size();
  if (in.records > 0) {
    in.last_time = source.last_time;
    last_time_ = std::max(last_time_, source.last_time);
  }
  done_bytes_ += source.file.size();
}

std::optional<std::string> CaptureReader::repeat_of(
    const Source& source, const std::vector<std::unique_ptr<Source>>& active) const {
  for (const auto& other : active) {
    if (other.get() == &source || other->packet.time != source.packet.time) continue;
    if (std::equal(source.packet.bytes.begin(), source.packet.bytes.end(),
                   other->packet.bytes.begin(), other->packet.bytes.end())) {
      return repeated_records_text(inputs_[source.slot].path, inputs_[other->slot].path,
                                   source.packet.time);
    }
  }
  return std::nullopt;
}

bool CaptureReader::read_raw(const std::string& path) {
  InputReport in;
  in.path = path;
  in.link_type = "plain bus bytes";
  in.file_bytes = file_size(path);
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    in.unreadable = true;
    in.error = std::strerror(errno);
    inputs_.push_back(in);
    return false;
  }
  std::vector<std::uint8_t> chunk(kRawChunk);
  pipeline_.begin_raw_input();
  for (;;) {
    const std::size_t n = std::fread(chunk.data(), 1, chunk.size(), f);
    if (n == 0) break;
    ++in.records;
    in.read_bytes += n;
    pipeline_.raw_bytes(std::span(chunk).first(n));
    progress_.update(done_bytes_ + in.read_bytes);
  }
  if (std::ferror(f) != 0) {
    in.truncated = true;
    in.error = "read error";
  }
  std::fclose(f);
  done_bytes_ += in.file_bytes;
  inputs_.push_back(in);
  return !in.truncated;
}

}  // namespace pvtap::analyzer
