#include "serial/serial_port.h"

#include <fcntl.h>
#include <linux/serial.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <utility>

namespace pvtap::analyzer {
namespace {

// The standard rates of --baud's range (1200 to 115200): those inverters' RS485 ports use,
// and those a rate search (--baud auto) tries.
constexpr std::array<std::pair<std::uint32_t, speed_t>, 8> kSpeeds{{
    {1200, B1200},
    {2400, B2400},
    {4800, B4800},
    {9600, B9600},
    {19200, B19200},
    {38400, B38400},
    {57600, B57600},
    {115200, B115200},
}};

std::optional<speed_t> speed_of(std::uint32_t baud) {
  for (const auto& [rate, speed] : kSpeeds) {
    if (rate == baud) return speed;
  }
  return std::nullopt;
}

std::string errno_text(const char* call) {
  return std::string(call) + ": " + std::strerror(errno);
}

tcflag_t character_format(SerialLine line) {
  tcflag_t flags = CS8 | CLOCAL | CREAD;
  if (line.parity != 'N') flags |= PARENB;
  if (line.parity == 'O') flags |= PARODD;
  if (line.stop_bits == 2) flags |= CSTOPB;
  return flags;
}

}  // namespace

std::string supported_speeds_text() {
  std::string text;
  for (const auto& entry : kSpeeds) {
    if (!text.empty()) text += ", ";
    text += std::to_string(entry.first);
  }
  return text;
}

SerialPort::~SerialPort() {
  close();
}

bool SerialPort::open(const std::string& path, std::uint32_t baud, SerialLine line,
                      bool mark_errors) {
  close();
  mark_errors_ = mark_errors;
  if (!speed_of(baud)) {
    error_ = "unsupported speed " + std::to_string(baud) +
             " baud (a serial tap takes: " + supported_speeds_text() + ")";
    return false;
  }
  // O_RDONLY: the tap listens and can never put a byte on the bus.
  fd_ = ::open(path.c_str(), O_RDONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    error_ = std::strerror(errno);
    if (errno == ENOENT) error_ += " (is the adapter plugged in? see ls /dev/serial/by-id/)";
    return false;
  }
  if (!configure(baud, line)) {
    close();
    return false;
  }
  return true;
}

bool SerialPort::configure(std::uint32_t baud, SerialLine line) {
  termios tio{};
  if (tcgetattr(fd_, &tio) != 0) {
    error_ = errno == ENOTTY ? "not a serial device" : errno_text("tcgetattr");
    return false;
  }
  cfmakeraw(&tio);
  tio.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | PARODD | CSTOPB | CRTSCTS);
  tio.c_cflag |= character_format(line);
  // Parity errors are counted by the driver (TIOCGICOUNT); the byte itself is kept as read,
  // so that every byte on the bus is accounted for in a frame or as noise.
  tio.c_iflag &= ~static_cast<tcflag_t>(INPCK | IGNPAR | PARMRK | IXON | IXOFF | IXANY);
  // A rate search needs to know which bytes failed: the driver then marks each framing or
  // parity error in the data (\377 \0 byte) and doubles a real \377.
  if (mark_errors_) tio.c_iflag |= INPCK | PARMRK;
  tio.c_cc[VMIN] = 1;
  tio.c_cc[VTIME] = 0;
  const speed_t speed = *speed_of(baud);
  if (cfsetispeed(&tio, speed) != 0 || cfsetospeed(&tio, speed) != 0) {
    error_ = "cannot set " + std::to_string(baud) + " baud: " + std::strerror(errno);
    return false;
  }
  if (tcsetattr(fd_, TCSANOW, &tio) != 0) {
    error_ = errno_text("tcsetattr");
    return false;
  }
  // tcsetattr succeeds when any one setting took; read back what the driver really set.
  termios set{};
  if (tcgetattr(fd_, &set) != 0) {
    error_ = errno_text("tcgetattr");
    return false;
  }
  if (cfgetispeed(&set) != speed) {
    error_ = "the driver refused " + std::to_string(baud) + " baud";
    return false;
  }
  const tcflag_t wanted = character_format(line) & (CSIZE | PARENB | PARODD | CSTOPB);
  if ((set.c_cflag & (CSIZE | PARENB | PARODD | CSTOPB)) != wanted) {
    error_ = std::string("the driver refused the character format 8") + line.parity +
             std::to_string(line.stop_bits) + " (data bits, parity, stop bits)";
    return false;
  }
  return true;
}

bool SerialPort::set_line(std::uint32_t baud, SerialLine line) {
  if (!speed_of(baud)) {
    error_ = "unsupported speed " + std::to_string(baud) + " baud";
    return false;
  }
  if (!configure(baud, line)) return false;
  // Bytes still queued were read at the old setting. Flushing input writes nothing.
  tcflush(fd_, TCIFLUSH);
  return true;
}

void SerialPort::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

SerialPort::ReadResult SerialPort::read(std::span<std::uint8_t> buffer, std::size_t& got) {
  got = 0;
  const ssize_t n = ::read(fd_, buffer.data(), buffer.size());
  if (n > 0) {
    got = static_cast<std::size_t>(n);
    return ReadResult::Data;
  }
  if (n < 0 && (errno == EAGAIN || errno == EINTR)) return ReadResult::Empty;
  // 0 is end of file on a hung-up tty; EIO/ENODEV/ENXIO an adapter or pty that went away.
  error_ = n == 0 ? "hung up" : errno_text("read");
  return ReadResult::Gone;
}

std::optional<LineErrorCounts> SerialPort::line_errors() {
  serial_icounter_struct counts{};
  if (ioctl(fd_, TIOCGICOUNT, &counts) != 0) {
    error_ = errno == ENOTTY || errno == EINVAL
                 ? "the driver does not count line errors (TIOCGICOUNT unsupported)"
                 : errno_text("TIOCGICOUNT");
    return std::nullopt;
  }
  LineErrorCounts c;
  c.framing = static_cast<std::uint64_t>(counts.frame);
  c.overrun = static_cast<std::uint64_t>(counts.overrun);
  c.parity = static_cast<std::uint64_t>(counts.parity);
  c.breaks = static_cast<std::uint64_t>(counts.brk);
  c.buffer_overrun = static_cast<std::uint64_t>(counts.buf_overrun);
  return c;
}

}  // namespace pvtap::analyzer
