#include "serial/usb_latency_timer.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>

namespace pvtap::analyzer {
namespace {

std::optional<int> read_ms(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  char text[16] = {};
  const ssize_t n = ::read(fd, text, sizeof text - 1);
  ::close(fd);
  if (n <= 0) return std::nullopt;
  return std::atoi(text);
}

// Writes "1"; an empty string on success, else why not.
std::string write_one_ms(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) return std::strerror(errno);
  const bool ok = ::write(fd, "1", 1) == 1;
  const std::string why = ok ? "" : std::strerror(errno);
  ::close(fd);
  return why;
}

// "ttyUSB0" for "/dev/serial/by-id/usb-FTDI...-port0" (a symlink to ../../ttyUSB0); the
// resolved path itself when it is not under `dev`.
std::string tty_name(const std::string& device_path, const std::string& dev) {
  char resolved[PATH_MAX];
  if (::realpath(device_path.c_str(), resolved) == nullptr) return {};
  const std::string full = resolved;
  const std::string prefix = dev + "/";
  return full.rfind(prefix, 0) == 0 ? full.substr(prefix.size()) : full;
}

}  // namespace

LatencyTimerState lower_latency_timer(const std::string& device_path, const TtyPlaces& places) {
  LatencyTimerState state;
  state.adapter = tty_name(device_path, places.dev);
  if (state.adapter.empty() || state.adapter.find('/') != std::string::npos) return state;
  const std::string timer = places.sys_class_tty + "/" + state.adapter + "/device/latency_timer";
  state.ms = read_ms(timer);
  if (!state.ms || *state.ms <= 1) return state;
  const int before = *state.ms;
  const std::string why = write_one_ms(timer);
  const std::optional<int> after = read_ms(timer);
  if (why.empty() && after && *after <= 1) {
    state.ms = after;
    state.note = "lowered from " + std::to_string(before) + " ms";
    return state;
  }
  state.note = "cannot lower it to 1 ms (" + (why.empty() ? std::string("not taken") : why) +
               "; run as root or add a udev rule)";
  return state;
}

}  // namespace pvtap::analyzer
