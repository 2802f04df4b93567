// The sentences pvtap answers Wireshark's extcap questions with, word for word.
// The suites start with a lower-case "extcap" so that `ctest -R extcap` selects them.
#include "extcap/extcap_sentences.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace pvtap::analyzer {
namespace {

TEST(extcapSentences, InterfacesAnswerListsEachPortAsAnRs485Tap) {
  const std::vector<DiscoveredPort> ports = {
      {"/dev/serial/by-id/usb-FTDI-port0", "ttyUSB0", "pvtap-usb-FTDI-port0"},
      {"/dev/pts/3", "pts/3", "pvtap-pts-3"}};
  EXPECT_EQ(interfaces_answer(ports),
            "extcap {version=" PVTAP_VERSION
            "}\n"
            "interface {value=pvtap-usb-FTDI-port0}{display=RS485 tap (ttyUSB0)}\n"
            "interface {value=pvtap-pts-3}{display=RS485 tap (pts/3)}\n");
}

TEST(extcapSentences, InterfacesAnswerWithoutPortsStillNamesTheProgram) {
  EXPECT_EQ(interfaces_answer({}), "extcap {version=" PVTAP_VERSION "}\n");
}

TEST(extcapSentences, DelimitersInNamesCannotBreakASentence) {
  const std::vector<DiscoveredPort> ports = {{"/tmp/a}b", "/tmp/a}{b\n", "pvtap-tmp-a}b"}};
  EXPECT_EQ(interfaces_answer(ports),
            "extcap {version=" PVTAP_VERSION
            "}\n"
            "interface {value=pvtap-tmp-a_b}{display=RS485 tap (/tmp/a__b_)}\n");
}

TEST(extcapSentences, DltsAnswerIsExportedPdus) {
  EXPECT_EQ(dlts_answer(),
            "dlt {number=252}{name=pvtap}"
            "{display=Exported PDUs (RS485 frames for the pvtap dissector)}\n");
}

// Two taps: the capture's own on ttyUSB0, and one that may hold the replies' pair.
const std::vector<DiscoveredPort> kTwoPorts = {{"/dev/ttyUSB0", "ttyUSB0", "pvtap-ttyUSB0"},
                                               {"/dev/ttyUSB1", "ttyUSB1", "pvtap-ttyUSB1"}};

TEST(extcapSentences, ConfigAnswerOffersFourSelectorsWithTheirDefaults) {
  const std::string config = config_answer(kTwoPorts, "pvtap-ttyUSB0");
  EXPECT_NE(config.find("arg {number=0}{call=--baud}{display=Baud rate}{type=selector}"
                        "{default=9600}"),
            std::string::npos);
  EXPECT_NE(config.find("arg {number=1}{call=--parity}{display=Parity}{type=selector}"
                        "{default=none}"),
            std::string::npos);
  EXPECT_NE(config.find("arg {number=2}{call=--stop-bits}{display=Stop bits}{type=selector}"
                        "{default=1}"),
            std::string::npos);
  EXPECT_NE(config.find("arg {number=3}{call=--dialect}{display=Dialect}{type=selector}"
                        "{default=auto}"),
            std::string::npos);
  EXPECT_NE(config.find("value {arg=0}{value=9600}{display=9600}{default=true}\n"),
            std::string::npos);
  EXPECT_NE(config.find("value {arg=0}{value=19200}{display=19200}\n"), std::string::npos);
  EXPECT_NE(config.find("value {arg=1}{value=none}{display=None}{default=true}\n"),
            std::string::npos);
  EXPECT_NE(config.find("value {arg=2}{value=2}{display=2}\n"), std::string::npos);
  EXPECT_NE(config.find("value {arg=3}{value=gsl}{display=GSL (KSTAR Modbus RTU)}\n"),
            std::string::npos);
}

TEST(extcapSentences, ConfigAnswerOffersTheOtherTapsAsTheRepliesPair) {
  const std::string config = config_answer(kTwoPorts, "pvtap-ttyUSB0");
  EXPECT_NE(config.find("arg {number=4}{call=--duplex-replies}"), std::string::npos) << config;
  EXPECT_NE(config.find("value {arg=4}{value=none}"), std::string::npos);
  EXPECT_NE(config.find("value {arg=4}{value=pvtap-ttyUSB1}{display=RS485 tap (ttyUSB1)}\n"),
            std::string::npos);
  // The capture's own tap cannot be its replies' pair.
  EXPECT_EQ(config.find("value {arg=4}{value=pvtap-ttyUSB0}"), std::string::npos);
}

TEST(extcapSentences, ConfigAnswerMarksExactlyOneDefaultPerSelector) {
  const std::string config = config_answer(kTwoPorts, "pvtap-ttyUSB0");
  std::size_t defaults = 0;
  for (std::size_t at = config.find("{default=true}"); at != std::string::npos;
       at = config.find("{default=true}", at + 1)) {
    ++defaults;
  }
  EXPECT_EQ(defaults, 5u);
  // Every line is one sentence: arg lines and value lines only.
  std::size_t start = 0;
  while (start < config.size()) {
    const std::size_t end = config.find('\n', start);
    ASSERT_NE(end, std::string::npos);
    const std::string line = config.substr(start, end - start);
    EXPECT_TRUE(line.rfind("arg {", 0) == 0 || line.rfind("value {", 0) == 0) << line;
    EXPECT_EQ(line.back(), '}') << line;
    start = end + 1;
  }
}

}  // namespace
}  // namespace pvtap::analyzer
