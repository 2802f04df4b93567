#include "sources/capture_reader.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "pvtap/capture/read_ahead_capture.h"

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

}  // namespace

std::optional<std::string> check_inputs(const std::vector<std::string>& captures,
                                        const std::vector<std::string>& raw_dumps) {
  for (const std::string& path : captures) {
    CaptureFile file;
    if (!file.open(path)) return path + ": " + file.error();
    if (!input_kind_of(file.link_type())) {
      return path + ": unsupported link type " + file.link_type_name() +
             "; supported: " + supported_link_types_text();
    }
  }
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

bool CaptureReader::read(const std::vector<std::string>& captures,
                         const std::vector<std::string>& raw_dumps) {
  std::uint64_t done = 0;
  for (const auto& path : captures) {
    // A truncated file ends the capture: what follows it would not join up.
    if (!read_capture(path, done)) return false;
    done += file_size(path);
  }
  bool complete = true;
  for (const auto& path : raw_dumps) {
    complete = read_raw(path, done) && complete;
    done += file_size(path);
  }
  return complete;
}

void CaptureReader::report_truncation() const {
  const InputReport& in = inputs_.back();
  std::fprintf(stderr,
               "pvtap: %s: truncated capture: %s (read %llu records, %llu of %llu bytes; "
               "results up to there are above)\n",
               in.path.c_str(), in.error.c_str(), static_cast<unsigned long long>(in.records),
               static_cast<unsigned long long>(in.read_bytes),
               static_cast<unsigned long long>(in.file_bytes));
}

bool CaptureReader::read_capture(const std::string& path, std::uint64_t done_before) {
  ReadAheadCapture file(read_ahead_);
  InputReport in;
  in.path = path;
  if (!file.open(path)) {
    in.truncated = true;
    in.error = file.error();
    inputs_.push_back(in);
    return false;
  }
  in.link_type = file.link_type_name();
  // Reading ahead to tell read chunks from characters costs a second open of the file: only
  // the input that decides the serial bus's timing is probed.
  const bool probe =
      input_kind_of(file.link_type()) == InputKind::Serial && pipeline_.serial_timing_open();
  pipeline_.begin_input(file.link_type(),
                        probe && largest_early_record(path, kTimingProbeRecords) > 1);
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
    pipeline_.record(packet);
    if (file.packets() % kProgressEvery == 0) progress_.update(done_before + file.position());
  }
  in.records = file.packets();
  in.file_bytes = file.size();
  in.read_bytes = in.truncated ? file.position() : file.size();
  inputs_.push_back(in);
  return !in.truncated;
}

bool CaptureReader::read_raw(const std::string& path, std::uint64_t done_before) {
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
  pipeline_.begin_raw_input();
  for (;;) {
    const std::size_t n = std::fread(chunk.data(), 1, chunk.size(), f);
    if (n == 0) break;
    ++in.records;
    in.read_bytes += n;
    pipeline_.raw_bytes(std::span(chunk).first(n));
    progress_.update(done_before + in.read_bytes);
  }
  if (std::ferror(f) != 0) {
    in.truncated = true;
    in.error = "read error";
  }
  std::fclose(f);
  inputs_.push_back(in);
  return !in.truncated;
}

}  // namespace pvtap::analyzer
