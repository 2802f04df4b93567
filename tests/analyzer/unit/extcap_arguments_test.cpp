// Reading Wireshark's extcap command lines: the questions, the capture settings, and what
// pvtap skips or refuses.
// The suites start with a lower-case "extcap" so that `ctest -R extcap` selects them.
#include "extcap/extcap_arguments.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace pvtap::analyzer {
namespace {

using Args = std::vector<std::string>;

TEST(extcapArguments, TellsExtcapCallsFromSubcommands) {
  EXPECT_TRUE(looks_like_extcap_call({"--extcap-interfaces", "--extcap-version=4.0"}));
  EXPECT_TRUE(looks_like_extcap_call({"--extcap-version=4.0", "--extcap-interfaces"}));
  EXPECT_TRUE(looks_like_extcap_call({"--capture", "--extcap-interface", "pvtap-ttyUSB0"}));
  EXPECT_TRUE(looks_like_extcap_call({"--extcap-interface=pvtap-ttyUSB0", "--extcap-dlts"}));
  EXPECT_FALSE(looks_like_extcap_call({}));
  EXPECT_FALSE(looks_like_extcap_call({"--help"}));
  // A subcommand comes first, whatever follows it.
  EXPECT_FALSE(looks_like_extcap_call({"sniff", "--device", "/dev/ttyUSB0", "--capture"}));
}

TEST(extcapArguments, ReadsEachQuestion) {
  EXPECT_EQ(parse_extcap_call({"--extcap-interfaces", "--extcap-version=4.0"}).action,
            ExtcapAction::ListInterfaces);
  const ExtcapCall dlts = parse_extcap_call({"--extcap-dlts", "--extcap-interface", "pvtap-x"});
  EXPECT_EQ(dlts.action, ExtcapAction::ListDlts);
  EXPECT_EQ(dlts.interface, "pvtap-x");
  const ExtcapCall config = parse_extcap_call({"--extcap-interface=pvtap-x", "--extcap-config"});
  EXPECT_EQ(config.action, ExtcapAction::ListConfig);
  EXPECT_EQ(config.interface, "pvtap-x");
  EXPECT_EQ(parse_extcap_call({"--extcap-version", "4.0"}).action, ExtcapAction::None);
}

TEST(extcapArguments, ReadsACaptureCallWithItsSettings) {
  const ExtcapCall call = parse_extcap_call(
      {"--capture", "--extcap-interface", "pvtap-ttyUSB0", "--fifo", "/tmp/wireshark_extcap_x",
       "--baud", "19200", "--parity=even", "--stop-bits", "2", "--dialect", "gsl"});
  EXPECT_EQ(call.action, ExtcapAction::Capture);
  EXPECT_EQ(call.interface, "pvtap-ttyUSB0");
  EXPECT_EQ(call.fifo, "/tmp/wireshark_extcap_x");
  EXPECT_EQ(call.settings.baud, "19200");
  EXPECT_EQ(call.settings.parity, "even");
  EXPECT_EQ(call.settings.stop_bits, "2");
  EXPECT_EQ(call.settings.dialect, "gsl");
  EXPECT_TRUE(call.capture_filter.empty());
  EXPECT_TRUE(call.problems.empty());
}

TEST(extcapArguments, SettingsNotPassedKeepTheDialogDefaults) {
  const ExtcapCall call =
      parse_extcap_call({"--capture", "--extcap-interface", "i", "--fifo", "f"});
  const ExtcapSettings defaults;
  EXPECT_EQ(call.settings.baud, defaults.baud);
  EXPECT_EQ(call.settings.parity, defaults.parity);
  EXPECT_EQ(call.settings.stop_bits, defaults.stop_bits);
  EXPECT_EQ(call.settings.dialect, defaults.dialect);
}

TEST(extcapArguments, AValueIsTakenAsGivenEvenWhenEmpty) {
  const ExtcapCall call =
      parse_extcap_call({"--extcap-capture-filter", "", "--extcap-interface", "i", "--capture"});
  EXPECT_EQ(call.action, ExtcapAction::Capture);
  EXPECT_EQ(call.capture_filter, "");
  EXPECT_EQ(call.interface, "i");
}

TEST(extcapArguments, AFilterWithoutActionIsAFilterCheck) {
  const ExtcapCall call =
      parse_extcap_call({"--extcap-interface", "pvtap-ttyUSB0", "--extcap-capture-filter", "tcp"});
  EXPECT_EQ(call.action, ExtcapAction::CheckFilter);
  EXPECT_EQ(call.capture_filter, "tcp");
  // With --capture it is a capture that was given a filter.
  EXPECT_EQ(parse_extcap_call({"--capture", "--extcap-capture-filter=tcp"}).action,
            ExtcapAction::Capture);
}

TEST(extcapArguments, UnknownOptionsAreSkippedWithTheirValue) {
  const ExtcapCall call = parse_extcap_call(
      {"--extcap-interfaces", "--debug", "--future-option", "value", "--other=x", "stray"});
  EXPECT_EQ(call.action, ExtcapAction::ListInterfaces);
  EXPECT_TRUE(call.problems.empty());
  EXPECT_EQ(call.ignored, (Args{"--debug", "--future-option", "value", "--other=x", "stray"}));
}

TEST(extcapArguments, AValueOptionAtTheEndIsAProblem) {
  const ExtcapCall call = parse_extcap_call({"--capture", "--fifo"});
  ASSERT_EQ(call.problems.size(), 1u);
  EXPECT_EQ(call.problems.front(), "--fifo needs a value");
}

}  // namespace
}  // namespace pvtap::analyzer
