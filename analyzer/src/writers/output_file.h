// OutputFile: a file written through an OutputStream (--values, --html), with one error
// style: open() and close() say why they failed.
#pragma once

#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "formatting/output_stream.h"

namespace pvtap::analyzer {

class OutputFile {
 public:
  OutputFile() = default;
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // Creates (or truncates) `path`; nullopt when it worked, else "PATH: reason".
  std::optional<std::string> open(const std::string& path);
  OutputStream& stream() { return *stream_; }
  // Writes what is buffered (only when something is: a live capture calls it often).
  void flush() {
    if (stream_ && !stream_->buffer().empty()) stream_->flush();
  }
  // Flushes and closes; nullopt when every byte reached the file, else "PATH: reason".
  std::optional<std::string> close();

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  std::unique_ptr<OutputStream> stream_;
};

}  // namespace pvtap::analyzer
