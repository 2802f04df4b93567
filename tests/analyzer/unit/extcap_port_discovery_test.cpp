// Finding serial ports in a fake /dev and /sys/class/tty built in a temporary folder.
// The suites start with a lower-case "extcap" so that `ctest -R extcap` selects them.
#include "extcap/extcap_port_discovery.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace pvtap::analyzer {
namespace {
namespace fs = std::filesystem;

class extcapFakeSystem : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "pvtap-ports-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    // Canonical, so that the expected paths compare equal to what discovery resolves.
    root_ = fs::canonical(pattern);
    places_.dev = (root_ / "dev").string();
    places_.sys_tty = (root_ / "sys" / "class" / "tty").string();
    fs::create_directories(root_ / "dev" / "serial" / "by-id");
    fs::create_directories(places_.sys_tty);
  }
  void TearDown() override { fs::remove_all(root_); }

  // A device node stands in as a plain file: discovery only looks at names and links.
  void node(const std::string& relative) {
    fs::create_directories((root_ / relative).parent_path());
    std::ofstream(root_ / relative).put('\0');
  }
  void by_id(const std::string& name, const std::string& target) {
    fs::create_symlink(target, root_ / "dev" / "serial" / "by-id" / name);
  }
  void uart(const std::string& name, const std::string& type) {
    fs::create_directories(fs::path(places_.sys_tty) / name);
    std::ofstream(fs::path(places_.sys_tty) / name / "type") << type << "\n";
  }
  std::string dev(const std::string& name) const { return (root_ / "dev" / name).string(); }

  fs::path root_;
  PortPlaces places_;
};

TEST_F(extcapFakeSystem, NothingFoundInAnEmptySystem) {
  EXPECT_TRUE(discover_serial_ports(places_).empty());
}

TEST_F(extcapFakeSystem, ListsAdaptersByIdThenUsbAcmAndUartsInNumericOrder) {
  for (const char* name :
       {"ttyUSB0", "ttyUSB2", "ttyUSB10", "ttyACM0", "ttyS0", "ttyS1", "ttyUSBx", "tty0", "ttyS"}) {
    node(std::string("dev/") + name);
  }
  by_id("usb-FTDI_FT232R_USB_UART_A10K1234-if00-port0", "../../ttyUSB2");
  uart("ttyS0", "4");  // a 16550A
  uart("ttyS1", "0");  // no UART behind the node
  uart("ttyS2", "4");  // a UART without a device node is skipped too
  const std::vector<DiscoveredPort> ports = discover_serial_ports(places_);
  ASSERT_EQ(ports.size(), 5u);
  EXPECT_EQ(ports[0].path, dev("serial/by-id/usb-FTDI_FT232R_USB_UART_A10K1234-if00-port0"));
  EXPECT_EQ(ports[0].name, "ttyUSB2");
  EXPECT_EQ(ports[0].interface, "pvtap-usb-FTDI_FT232R_USB_UART_A10K1234-if00-port0");
  EXPECT_EQ(ports[1].path, dev("ttyUSB0"));
  EXPECT_EQ(ports[1].name, "ttyUSB0");
  EXPECT_EQ(ports[1].interface, "pvtap-ttyUSB0");
  EXPECT_EQ(ports[2].name, "ttyUSB10");
  EXPECT_EQ(ports[3].name, "ttyACM0");
  EXPECT_EQ(ports[4].path, dev("ttyS0"));
  EXPECT_EQ(ports[4].interface, "pvtap-ttyS0");
}

TEST_F(extcapFakeSystem, SkipsByIdLinksOfAdaptersThatAreGone) {
  node("dev/ttyUSB1");
  by_id("usb-gone-port0", "../../ttyUSB7");
  const std::vector<DiscoveredPort> ports = discover_serial_ports(places_);
  ASSERT_EQ(ports.size(), 1u);
  EXPECT_EQ(ports[0].interface, "pvtap-ttyUSB1");
}

TEST_F(extcapFakeSystem, AddsExtraPortsThatExistOnceEach) {
  node("dev/ttyUSB0");
  node("dev/pts/3");
  node("elsewhere/ttyV0");
  places_.extra = {dev("pts/3"), dev("pts/9"), (root_ / "elsewhere" / "ttyV0").string(),
                   dev("ttyUSB0"), dev("pts/3")};
  const std::vector<DiscoveredPort> ports = discover_serial_ports(places_);
  ASSERT_EQ(ports.size(), 3u);
  EXPECT_EQ(ports[0].name, "ttyUSB0");
  EXPECT_EQ(ports[1].path, dev("pts/3"));
  EXPECT_EQ(ports[1].name, "pts/3");
  EXPECT_EQ(ports[1].interface, "pvtap-pts-3");
  const std::string outside = (root_ / "elsewhere" / "ttyV0").string();
  EXPECT_EQ(ports[2].name, outside);
  std::string id = outside.substr(1);
  std::replace(id.begin(), id.end(), '/', '-');
  EXPECT_EQ(ports[2].interface, "pvtap-" + id);
}

TEST(extcapPortList, SplitsOnColonsAndSkipsEmptyEntries) {
  EXPECT_EQ(split_port_list("/dev/pts/3:/tmp/ttyV0"),
            (std::vector<std::string>{"/dev/pts/3", "/tmp/ttyV0"}));
  EXPECT_EQ(split_port_list(":/dev/pts/3::"), (std::vector<std::string>{"/dev/pts/3"}));
  EXPECT_TRUE(split_port_list("").empty());
}

TEST(extcapPortList, SystemPlacesReadTheEnvironment) {
  ::setenv(kExtraPortsVariable, "/dev/pts/4:/dev/pts/5", 1);
  const PortPlaces places = system_port_places();
  ::unsetenv(kExtraPortsVariable);
  EXPECT_EQ(places.dev, "/dev");
  EXPECT_EQ(places.sys_tty, "/sys/class/tty");
  EXPECT_EQ(places.extra, (std::vector<std::string>{"/dev/pts/4", "/dev/pts/5"}));
  EXPECT_TRUE(system_port_places().extra.empty());
}

}  // namespace
}  // namespace pvtap::analyzer
