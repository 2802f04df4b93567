// SerialPort, the USB latency timer and DeviceTap's reopening, on real pseudo-terminals and a
// throw-away sysfs-like tree.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "serial/device_tap.h"
#include "serial/serial_port.h"
#include "serial/usb_latency_timer.h"

namespace pvtap::analyzer {
namespace {

namespace fs = std::filesystem;

// A pseudo-terminal whose slave side the code under test opens by name.
class Pty {
 public:
  Pty() {
    char name[128] = {};
    if (::openpty(&master_, &slave_, name, nullptr, nullptr) != 0) ADD_FAILURE() << "openpty";
    path_ = name;
  }
  ~Pty() { hang_up(); }
  Pty(const Pty&) = delete;
  Pty& operator=(const Pty&) = delete;

  const std::string& path() const { return path_; }
  int slave() const { return slave_; }
  void write(const std::string& bytes) const {
    ASSERT_EQ(::write(master_, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
  }
  void hang_up() {
    if (slave_ >= 0) ::close(slave_);
    if (master_ >= 0) ::close(master_);
    slave_ = master_ = -1;
  }

 private:
  int master_ = -1;
  int slave_ = -1;
  std::string path_;
};

termios settings_of(int fd) {
  termios t{};
  EXPECT_EQ(tcgetattr(fd, &t), 0);
  return t;
}

TEST(SerialPort, OpensReadOnlyInRawModeAtTheLinesSettings) {
  Pty pty;
  SerialPort port;
  ASSERT_TRUE(port.open(pty.path(), 19200, SerialLine{'N', 2})) << port.error();
  const int flags = ::fcntl(port.fd(), F_GETFL);
  EXPECT_EQ(flags & O_ACCMODE, O_RDONLY);
  EXPECT_NE(flags & O_NONBLOCK, 0);
  EXPECT_NE(::fcntl(port.fd(), F_GETFD) & FD_CLOEXEC, 0);
  const termios t = settings_of(pty.slave());
  EXPECT_EQ(cfgetispeed(&t), static_cast<speed_t>(B19200));
  EXPECT_EQ(t.c_cflag & CSIZE, static_cast<tcflag_t>(CS8));
  EXPECT_EQ(t.c_cflag & PARENB, 0u);
  EXPECT_NE(t.c_cflag & CSTOPB, 0u);
  EXPECT_NE(t.c_cflag & CLOCAL, 0u);
  EXPECT_NE(t.c_cflag & CREAD, 0u);
  EXPECT_EQ(t.c_cflag & CRTSCTS, 0u);
  EXPECT_EQ(t.c_iflag & (IXON | IXOFF | ICRNL | ISTRIP), 0u);
  EXPECT_EQ(t.c_lflag & (ICANON | ECHO | ISIG), 0u);
  EXPECT_EQ(t.c_oflag & OPOST, 0u);
}

// Linux ptys drop PARENB from every termios change; a tap whose driver will not check
// parity would misread the bus, so pvtap reads the settings back and refuses.
TEST(SerialPort, ADriverThatDropsParityIsRefused) {
  Pty pty;
  SerialPort port;
  EXPECT_FALSE(port.open(pty.path(), 9600, SerialLine{'E', 1}));
  EXPECT_NE(port.error().find("character format 8E1"), std::string::npos) << port.error();
  EXPECT_FALSE(port.is_open());
}

TEST(SerialPort, AnUnsupportedSpeedIsNamed) {
  Pty pty;
  SerialPort port;
  EXPECT_FALSE(port.open(pty.path(), 14400, SerialLine{}));
  EXPECT_NE(port.error().find("14400"), std::string::npos) << port.error();
  EXPECT_NE(port.error().find("115200"), std::string::npos) << port.error();
  EXPECT_FALSE(port.is_open());
}

TEST(SerialPort, ReadsDataThenEmptyThenGoneWhenTheOtherSideCloses) {
  Pty pty;
  SerialPort port;
  ASSERT_TRUE(port.open(pty.path(), 9600, SerialLine{})) << port.error();
  std::array<std::uint8_t, 64> buffer{};
  std::size_t got = 0;
  EXPECT_EQ(port.read(buffer, got), SerialPort::ReadResult::Empty);
  pty.write(std::string("\x01\x03\x00\x0a", 4));
  ::usleep(20000);
  ASSERT_EQ(port.read(buffer, got), SerialPort::ReadResult::Data);
  EXPECT_EQ(got, 4u);
  EXPECT_EQ(buffer[3], 0x0a);
  EXPECT_EQ(port.read(buffer, got), SerialPort::ReadResult::Empty);
  pty.hang_up();
  EXPECT_EQ(port.read(buffer, got), SerialPort::ReadResult::Gone);
}

TEST(SerialPort, ErrorsNameTheProblem) {
  SerialPort port;
  EXPECT_FALSE(port.open("/dev/pvtap-no-such-tty", 9600, SerialLine{}));
  EXPECT_NE(port.error().find("No such file"), std::string::npos) << port.error();
  EXPECT_NE(port.error().find("/dev/serial/by-id"), std::string::npos) << port.error();
  const fs::path file = fs::temp_directory_path() / "pvtap-not-a-tty";
  std::ofstream(file) << "x";
  EXPECT_FALSE(port.open(file.string(), 9600, SerialLine{}));
  EXPECT_NE(port.error().find("not a serial device"), std::string::npos) << port.error();
  fs::remove(file);
}

TEST(SerialPort, APtyCountsNoLineErrorsAndSaysSo) {
  Pty pty;
  SerialPort port;
  ASSERT_TRUE(port.open(pty.path(), 9600, SerialLine{})) << port.error();
  EXPECT_FALSE(port.line_errors().has_value());
  EXPECT_NE(port.error().find("TIOCGICOUNT"), std::string::npos) << port.error();
}

// A tree shaped like /dev and /sys/class/tty with one FTDI adapter behind a by-id link.
class FakeAdapter : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("pvtap-tty-" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "dev" / "serial" / "by-id");
    std::ofstream(root_ / "dev" / "ttyUSB0") << "";
    fs::create_symlink("../../ttyUSB0", by_id());
    fs::create_directories(root_ / "sys" / "ttyUSB0" / "device");
    places_ = TtyPlaces{(root_ / "dev").string(), (root_ / "sys").string()};
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path by_id() const { return root_ / "dev" / "serial" / "by-id" / "usb-FTDI_A10K-port0"; }
  fs::path timer() const { return root_ / "sys" / "ttyUSB0" / "device" / "latency_timer"; }
  int timer_ms() const {
    int ms = -1;
    std::ifstream(timer()) >> ms;
    return ms;
  }

  fs::path root_;
  TtyPlaces places_;
};

TEST_F(FakeAdapter, LowersAWritableTimerTo1Ms) {
  std::ofstream(timer()) << "16\n";
  const LatencyTimerState state = lower_latency_timer(by_id().string(), places_);
  EXPECT_EQ(state.adapter, "ttyUSB0");
  ASSERT_TRUE(state.ms.has_value());
  EXPECT_EQ(*state.ms, 1);
  EXPECT_EQ(state.note, "lowered from 16 ms");
  EXPECT_EQ(timer_ms(), 1);
}

TEST_F(FakeAdapter, LeavesA1MsTimerAlone) {
  std::ofstream(timer()) << "1\n";
  const LatencyTimerState state = lower_latency_timer(by_id().string(), places_);
  ASSERT_TRUE(state.ms.has_value());
  EXPECT_EQ(*state.ms, 1);
  EXPECT_EQ(state.note, "");
}

TEST_F(FakeAdapter, AnAdapterWithoutTimerHasNone) {
  const LatencyTimerState state = lower_latency_timer(by_id().string(), places_);
  EXPECT_EQ(state.adapter, "ttyUSB0");
  EXPECT_FALSE(state.ms.has_value());
}

TEST(DeviceTap, RetriesAfterADoublingBackoffAndCountsTheOutage) {
  DeviceTap tap("/dev/pvtap-no-such-tty", 9600, SerialLine{});
  EXPECT_FALSE(tap.open());
  tap.went_away(100.0);
  EXPECT_TRUE(tap.outage().ongoing());
  EXPECT_DOUBLE_EQ(tap.outage().next_attempt(), 100.1);
  EXPECT_FALSE(tap.try_reopen(100.1));
  EXPECT_DOUBLE_EQ(tap.outage().next_attempt(), 100.3);
  double now = 100.3;
  for (int i = 0; i < 10; ++i) {
    EXPECT_FALSE(tap.try_reopen(now));
    if (i < 10 - 1) now = tap.outage().next_attempt();
  }
  // 0.1, 0.2, 0.4, ... doubles up to 2 s and stays there.
  EXPECT_DOUBLE_EQ(tap.outage().next_attempt() - now, 2.0);
  const DeviceReport report = tap.report(now + 1.0);
  EXPECT_EQ(report.outages, 1u);
  EXPECT_TRUE(report.lost_at_end);
  EXPECT_DOUBLE_EQ(report.outage_seconds, now + 1.0 - 100.0);
  EXPECT_NE(report.last_error.find("No such file"), std::string::npos);
}

TEST(DeviceTap, ComesBackWhenThePathLeadsToADeviceAgain) {
  const fs::path link = fs::temp_directory_path() / ("pvtap-link-" + std::to_string(::getpid()));
  fs::remove(link);
  Pty first;
  fs::create_symlink(first.path(), link);
  DeviceTap tap(link.string(), 9600, SerialLine{});
  ASSERT_TRUE(tap.open()) << tap.error();
  tap.went_away(10.0);
  fs::remove(link);
  EXPECT_FALSE(tap.try_reopen(10.1));
  Pty second;
  fs::create_symlink(second.path(), link);
  EXPECT_TRUE(tap.try_reopen(10.3));
  EXPECT_FALSE(tap.outage().ongoing());
  const DeviceReport report = tap.report(11.0);
  EXPECT_EQ(report.outages, 1u);
  EXPECT_FALSE(report.lost_at_end);
  EXPECT_NEAR(report.outage_seconds, 0.3, 1e-9);
  fs::remove(link);
}

}  // namespace
}  // namespace pvtap::analyzer
