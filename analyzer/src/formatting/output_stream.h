// OutputStream: buffered writing to stdout (or any FILE*) with one system call per 64 KiB.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace pvtap::analyzer {

class OutputStream {
 public:
  explicit OutputStream(std::FILE* file) : file_(file) { buffer_.reserve(kFlushAt + 4096); }
  ~OutputStream() { flush(); }
  OutputStream(const OutputStream&) = delete;
  OutputStream& operator=(const OutputStream&) = delete;

  // Writers append to the buffer directly, then call done() once per line or block.
  std::string& buffer() { return buffer_; }
  void done() {
    if (buffer_.size() >= kFlushAt) flush();
  }
  void write(std::string_view text) {
    buffer_ += text;
    done();
  }
  void flush() {
    if (!buffer_.empty()) std::fwrite(buffer_.data(), 1, buffer_.size(), file_);
    buffer_.clear();
    std::fflush(file_);
  }
  bool failed() const { return std::ferror(file_) != 0; }

 private:
  static constexpr std::size_t kFlushAt = 64 * 1024;
  std::FILE* file_;
  std::string buffer_;
};

}  // namespace pvtap::analyzer
