// LastErrorLine: libmosquitto's last error log line, which names what a bare error code does
// not (the TLS verification that failed, the address refused).
#pragma once

#include <mutex>
#include <string>

namespace pvtap::analyzer {

// Its own lock, apart from the client's mutex: libmosquitto logs from inside publish calls,
// which run with that mutex held.
class LastErrorLine {
 public:
  void keep(const char* text);
  // " (the line)" to end an error message with, or nothing.
  std::string detail();

 private:
  std::mutex mutex_;
  std::string text_;
};

}  // namespace pvtap::analyzer
