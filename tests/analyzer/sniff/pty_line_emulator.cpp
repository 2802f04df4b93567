// pty-line-emulator: a pseudo-terminal that behaves like a serial line. A pty ignores the
// rate and format its reader sets; this one reads them back (tcgetattr on the slave) before
// every transmission and delivers only what a UART set that way would receive from the true
// line: the bytes themselves when it matches, garbage when it does not.
//
// usage: pty-line-emulator BAUD FORMAT      (FORMAT: 8N1, 8N2, 8E1, 8O1, ...)
// Prints the slave's path on stdout, then reads lines "OFFSET HEX" from stdin: OFFSET seconds
// after the first line, the bytes HEX cross the line back to back. Exits at the end of stdin.
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "uart_receiver.h"

namespace {

using pvtap::LineSetting;
using pvtap::Parity;

constexpr std::array<std::pair<speed_t, std::uint32_t>, 8> kSpeeds{{
    {B1200, 1200},
    {B2400, 2400},
    {B4800, 4800},
    {B9600, 9600},
    {B19200, 19200},
    {B38400, 38400},
    {B57600, 57600},
    {B115200, 115200},
}};

// What the reader set the slave to: a rate this tool does not know reads as 9600.
LineSetting reader_setting(int slave) {
  termios tio{};
  LineSetting s;
  if (tcgetattr(slave, &tio) != 0) return s;
  for (const auto& [speed, baud] : kSpeeds) {
    if (cfgetispeed(&tio) == speed) s.baud = baud;
  }
  if ((tio.c_cflag & PARENB) != 0) {
    s.format.parity = (tio.c_cflag & PARODD) != 0 ? Parity::Odd : Parity::Even;
  }
  s.format.stop_bits = (tio.c_cflag & CSTOPB) != 0 ? 2 : 1;
  return s;
}

bool parse_format(const std::string& text, LineSetting& line) {
  if (text.size() != 3 || text[0] != '8') return false;
  line.format.parity = text[1] == 'E' ? Parity::Even : text[1] == 'O' ? Parity::Odd : Parity::None;
  line.format.stop_bits = text[2] == '2' ? 2 : 1;
  return text[1] == 'N' || text[1] == 'E' || text[1] == 'O';
}

std::vector<std::uint8_t> from_hex(const std::string& hex) {
  std::vector<std::uint8_t> out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) {
    out.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  }
  return out;
}

// The characters the reader's UART makes of `bytes`, as a tty without error marks hands
// them over (a break as 0x00).
std::vector<std::uint8_t> delivered(const std::vector<std::uint8_t>& bytes, const LineSetting& line,
                                    int slave) {
  std::vector<std::uint8_t> out;
  for (const pvtap::UartCharacter& c : pvtap::test::received(bytes, line, reader_setting(slave))) {
    out.push_back(c.is_break ? 0 : static_cast<std::uint8_t>(c.value));
  }
  return out;
}

void write_all(int fd, const std::vector<std::uint8_t>& data) {
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n <= 0) return;  // the reader went away
    done += static_cast<std::size_t>(n);
  }
}

}  // namespace

int main(int argc, char** argv) {
  LineSetting line;
  if (argc != 3 || !parse_format(argv[2], line)) {
    std::fprintf(stderr, "usage: pty-line-emulator BAUD FORMAT (e.g. 19200 8E1)\n");
    return 2;
  }
  line.baud = static_cast<std::uint32_t>(std::stoul(argv[1]));
  int master = -1;
  int slave = -1;
  termios raw{};
  cfmakeraw(&raw);
  if (openpty(&master, &slave, nullptr, &raw, nullptr) != 0) {
    std::perror("openpty");
    return 2;
  }
  std::printf("%s\n", ttyname(slave));
  std::fflush(stdout);
  std::string text;
  bool started = false;
  auto start = std::chrono::steady_clock::now();
  while (std::getline(std::cin, text)) {
    std::istringstream fields(text);
    double offset = 0;
    std::string hex;
    if (!(fields >> offset >> hex)) continue;
    if (!started) start = std::chrono::steady_clock::now();
    started = true;
    std::this_thread::sleep_until(start + std::chrono::duration<double>(offset));
    write_all(master, delivered(from_hex(hex), line, slave));
  }
  ::close(slave);
  ::close(master);
  return 0;
}
