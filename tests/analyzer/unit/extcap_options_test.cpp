// The options dialog's settings: their table, their check, and the capture they make.
// The suites start with a lower-case "extcap" so that `ctest -R extcap` selects them.
#include "extcap/extcap_options.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "extcap/extcap_capture.h"

namespace pvtap::analyzer {
namespace {

bool offers(const ExtcapOption& option, const std::string& value) {
  return std::any_of(option.choices.begin(), option.choices.end(),
                     [&value](const ExtcapChoice& c) { return c.value == value; });
}

TEST(extcapOptions, OffersBaudParityStopBitsAndDialectInThatOrder) {
  std::vector<std::string> calls;
  for (const ExtcapOption& option : extcap_options()) calls.push_back(option.call);
  EXPECT_EQ(calls, (std::vector<std::string>{"--baud", "--parity", "--stop-bits", "--dialect"}));
}

TEST(extcapOptions, EachDefaultIsOneOfItsChoicesAndTheParsersDefault) {
  const ExtcapSettings defaults;
  for (const ExtcapOption& option : extcap_options()) {
    EXPECT_TRUE(offers(option, option.default_value)) << option.call;
    EXPECT_EQ(option.default_value, defaults.*option.setting) << option.call;
  }
  EXPECT_TRUE(settings_problems(defaults).empty());
}

TEST(extcapOptions, OffersTheUsualRatesAndAllDialects) {
  const ExtcapOption& baud = extcap_options().at(0);
  for (const char* rate : {"2400", "4800", "9600", "19200", "38400", "57600", "115200", "auto"}) {
    EXPECT_TRUE(offers(baud, rate)) << rate;
  }
  const ExtcapOption& dialect = extcap_options().at(3);
  for (const char* name : {"auto", "ascii", "hybrid", "gsl", "modbus"}) {
    EXPECT_TRUE(offers(dialect, name)) << name;
  }
}

TEST(extcapOptions, ValuesOutsideTheChoicesAreProblems) {
  ExtcapSettings settings;
  settings.baud = "1234";
  settings.parity = "mark";
  settings.stop_bits = "1.5";
  settings.dialect = "profibus";
  const std::vector<std::string> problems = settings_problems(settings);
  ASSERT_EQ(problems.size(), 4u);
  EXPECT_EQ(problems[0],
            "--baud 1234: not one of 2400, 4800, 9600, 19200, 38400, 57600, 115200, auto");
  EXPECT_EQ(problems[1], "--parity mark: not one of none, even, odd");
  EXPECT_EQ(problems[2], "--stop-bits 1.5: not one of 1, 2");
  EXPECT_EQ(problems[3], "--dialect profibus: not one of auto, ascii, hybrid, gsl, modbus");
}

TEST(extcapOptions, AutoBaudSearchesTheTapsSettings) {
  const DiscoveredPort port{"/dev/ttyUSB0", "ttyUSB0", "pvtap-ttyUSB0"};
  ExtcapSettings settings;
  settings.baud = "auto";
  EXPECT_TRUE(settings_problems(settings).empty());
  EXPECT_TRUE(capture_options(port, settings, "/tmp/fifo").live.search_line);
}

TEST(extcapOptions, ACaptureSniffsThePortWithTheSettingsIntoTheFifo) {
  const DiscoveredPort port{"/dev/serial/by-id/usb-FTDI-port0", "ttyUSB0", "pvtap-usb-FTDI-port0"};
  ExtcapSettings settings;
  settings.baud = "19200";
  settings.parity = "even";
  settings.stop_bits = "2";
  settings.dialect = "hybrid";
  const SniffOptions o = capture_options(port, settings, "/tmp/fifo");
  EXPECT_EQ(o.live.devices, (std::vector<std::string>{"/dev/serial/by-id/usb-FTDI-port0"}));
  EXPECT_EQ(o.baud, 19200u);
  EXPECT_EQ(o.live.line.parity, 'E');
  EXPECT_EQ(o.live.line.stop_bits, 2);
  EXPECT_EQ(o.dialect, "hybrid");
  EXPECT_EQ(o.write_path, "/tmp/fifo");
  EXPECT_TRUE(o.live.quiet);
  EXPECT_TRUE(o.summary_only);
  EXPECT_FALSE(o.live.search_line);
  settings.parity = "odd";
  EXPECT_EQ(capture_options(port, settings, "f").live.line.parity, 'O');
  settings.parity = "none";
  settings.stop_bits = "1";
  EXPECT_EQ(capture_options(port, settings, "f").live.line.parity, 'N');
  EXPECT_EQ(capture_options(port, settings, "f").live.line.stop_bits, 1);
}

}  // namespace
}  // namespace pvtap::analyzer
