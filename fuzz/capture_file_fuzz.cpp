// Fuzz target capture_file: arbitrary bytes as a pcap or pcapng file through libpcap into the
// whole `pvtap audit` pipeline (link types, IP/TCP/UDP decoding, TCP reassembly, exported PDUs,
// serial records, bus sessions, writers, report). The file is an in-memory file (memfd) opened
// by its /proc path, so the audit reads it exactly as it reads a file on disk. The last byte
// picks the output format and whether --write is on.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "cli/audit_command.h"
#include "cli/common_options.h"
#include "cli/exit_status.h"
#include "formatting/output_stream.h"
#include "fuzz_input.h"
#include "pvtap/registers/register_decoder.h"
#include "sources/capture_reader.h"

namespace {

// MemoryFile: the input as a file that lives only in memory.
class MemoryFile {
 public:
  MemoryFile(const std::uint8_t* data, std::size_t size) : fd_(::memfd_create("capture", 0)) {
    PVTAP_FUZZ_CHECK(fd_ >= 0);
    std::size_t written = 0;
    while (written < size) {
      const ssize_t n = ::write(fd_, data + written, size - written);
      PVTAP_FUZZ_CHECK(n > 0);
      written += static_cast<std::size_t>(n);
    }
  }
  ~MemoryFile() { ::close(fd_); }
  MemoryFile(const MemoryFile&) = delete;
  MemoryFile& operator=(const MemoryFile&) = delete;
  std::string path() const { return "/proc/self/fd/" + std::to_string(fd_); }

 private:
  int fd_;
};

std::FILE* null_file() {
  static std::FILE* file = std::fopen("/dev/null", "w");
  return file;
}

// pvtap's one-line error messages go nowhere while the audit runs; sanitizer reports still
// reach file descriptor 2, which they write to directly.
class QuietStderr {
 public:
  QuietStderr() : saved_(stderr) { stderr = null_file(); }
  ~QuietStderr() { stderr = saved_; }
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;

 private:
  std::FILE* saved_;
};

pvtap::analyzer::AuditOptions options_for(const std::string& path, std::uint8_t selector) {
  static const char* const kFormats[] = {"text", "jsonl", "csv", "jsonl"};
  pvtap::analyzer::AuditOptions o;
  o.captures = {path};
  o.format_name = kFormats[selector & 3u];
  o.summary_only = (selector & 4u) != 0;
  if (selector & 8u) o.write_path = "/dev/null";
  pvtap::analyzer::apply_choices(o);
  return o;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const pvtap::RegisterDecoder decoder;
  const MemoryFile file(data, size);
  const auto options = options_for(file.path(), data[size - 1]);
  QuietStderr quiet;
  pvtap::analyzer::OutputStream out(null_file());
  const int status = pvtap::analyzer::audit(options, decoder, out);
  PVTAP_FUZZ_CHECK(status == pvtap::analyzer::kExitOk || status == pvtap::analyzer::kExitBadInput ||
                   status == pvtap::analyzer::kExitFindings);
  return 0;
}
