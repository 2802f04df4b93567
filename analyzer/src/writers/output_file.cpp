// OutputFile: opening, flushing and closing with the reason of any failure.
#include "writers/output_file.h"

#include <cerrno>
#include <cstring>

namespace pvtap::analyzer {

OutputFile::~OutputFile() {
  (void)close();
}

std::optional<std::string> OutputFile::open(const std::string& path) {
  path_ = path;
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) return path + ": " + std::strerror(errno);
  stream_ = std::make_unique<OutputStream>(file_);
  return std::nullopt;
}

std::optional<std::string> OutputFile::close() {
  if (file_ == nullptr) return std::nullopt;
  stream_->flush();
  const bool write_failed = stream_->failed();
  const int saved = errno;
  stream_.reset();
  const bool close_failed = std::fclose(file_) != 0;
  file_ = nullptr;
  if (write_failed) return path_ + ": " + std::strerror(saved != 0 ? saved : EIO);
  if (close_failed) return path_ + ": " + std::strerror(errno);
  return std::nullopt;
}

}  // namespace pvtap::analyzer
