#include "outputs/serial_pacer.h"

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>

namespace pvtap::sim {
namespace {

speed_t speed_of(unsigned baud) {
  switch (baud) {
    case 1200:
      return B1200;
    case 2400:
      return B2400;
    case 4800:
      return B4800;
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    default:
      return B0;
  }
}

// Raw 8N1 at the baud; a pty accepts the settings and ignores the speed, so the pacing below
// is what gives it the bus's timing.
bool configure(int fd, unsigned baud) {
  termios tio{};
  if (tcgetattr(fd, &tio) != 0) return false;
  cfmakeraw(&tio);
  tio.c_cflag &= ~static_cast<tcflag_t>(PARENB | CSTOPB | CSIZE);
  tio.c_cflag |= CS8 | CLOCAL | CREAD;
  cfsetispeed(&tio, speed_of(baud));
  cfsetospeed(&tio, speed_of(baud));
  return tcsetattr(fd, TCSANOW, &tio) == 0;
}

timespec plus_micros(timespec t, Micros us) {
  t.tv_sec += static_cast<time_t>(us / 1'000'000);
  t.tv_nsec += static_cast<long>(us % 1'000'000) * 1000;
  if (t.tv_nsec >= 1'000'000'000) {
    t.tv_sec += 1;
    t.tv_nsec -= 1'000'000'000;
  }
  return t;
}

void sleep_until(const timespec& t) {
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, nullptr) == EINTR) {
  }
}

// Opened and configured, or -1 with `error` set.
int open_device(const std::string& device, unsigned baud, std::string& error) {
  const int fd = open(device.c_str(), O_WRONLY | O_NOCTTY);
  if (fd < 0) {
    error = device + ": " + std::strerror(errno);
    return -1;
  }
  if (!configure(fd, baud)) {
    error = device + ": " + std::strerror(errno);
    close(fd);
    return -1;
  }
  return fd;
}

// Each event onto the device its side drives (`fds[0]` for requests, `fds[1]` for the rest).
std::string pace(const BusTimeline& timeline, const int (&fds)[2],
                 const std::vector<std::string>& devices, unsigned baud) {
  timespec origin{};
  clock_gettime(CLOCK_MONOTONIC, &origin);
  const Micros first = timeline.events.empty() ? 0 : timeline.events.front().start;
  const Micros char_us = static_cast<Micros>(10'000'000 / baud);
  std::string error;
  for (const BusEvent& e : timeline.events) {
    const std::size_t side = e.role == Role::Request ? 0 : 1;
    for (std::size_t i = 0; i < e.bytes.size() && error.empty(); ++i) {
      sleep_until(plus_micros(origin, e.start - first + static_cast<Micros>(i) * char_us));
      if (write(fds[side], &e.bytes[i], 1) != 1) {
        error = devices[side] + ": " + std::strerror(errno);
      }
    }
  }
  for (const int fd : fds) tcdrain(fd);
  return error;
}

}  // namespace

std::string pace_onto_device(const BusTimeline& timeline, const std::string& device,
                             unsigned baud) {
  if (speed_of(baud) == B0) return "unsupported baud " + std::to_string(baud);
  std::string error;
  const int fd = open_device(device, baud, error);
  if (fd < 0) return error;
  const int fds[2] = {fd, fd};
  error = pace(timeline, fds, {device, device}, baud);
  close(fd);
  return error;
}

std::string pace_onto_duplex(const BusTimeline& timeline, const std::vector<std::string>& devices,
                             unsigned baud) {
  if (speed_of(baud) == B0) return "unsupported baud " + std::to_string(baud);
  std::string error;
  const int requests = open_device(devices.at(0), baud, error);
  if (requests < 0) return error;
  const int replies = open_device(devices.at(1), baud, error);
  if (replies < 0) {
    close(requests);
    return error;
  }
  const int fds[2] = {requests, replies};
  error = pace(timeline, fds, devices, baud);
  close(requests);
  close(replies);
  return error;
}

}  // namespace pvtap::sim
