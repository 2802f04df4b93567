// LiveCapture's filter text, and its refusals that need no capture rights to provoke.
#include <gtest/gtest.h>

#include <string>

#include "sources/live_capture.h"

namespace pvtap::analyzer {
namespace {

TEST(LiveCaptureFilter, PortsMatchTcpAndUdpOnEitherSide) {
  EXPECT_EQ(live_capture_filter({4001}, ""), "(tcp port 4001 or udp port 4001)");
  EXPECT_EQ(live_capture_filter({4001, 502}, ""),
            "(tcp port 4001 or udp port 4001 or tcp port 502 or udp port 502)");
}

TEST(LiveCaptureFilter, UserFilterIsAndedInItsOwnParentheses) {
  // Parentheses keep an "or" in the user's filter from escaping the port clause.
  EXPECT_EQ(live_capture_filter({4001}, "host 10.0.0.2 or host 10.0.0.3"),
            "(tcp port 4001 or udp port 4001) and (host 10.0.0.2 or host 10.0.0.3)");
  EXPECT_EQ(live_capture_filter({}, "host 10.0.0.2"), "(host 10.0.0.2)");
}

TEST(LiveCaptureFilter, NothingGivenCapturesEverything) {
  EXPECT_EQ(live_capture_filter({}, ""), "");
}

TEST(LiveCapture, UnknownInterfaceIsRefusedWithAReason) {
  LiveCapture capture;
  EXPECT_FALSE(capture.open(LiveCaptureSettings{"pvtap-none0", {4001}, ""}));
  EXPECT_FALSE(capture.error().empty());
  EXPECT_EQ(capture.packets(), 0u);
}

}  // namespace
}  // namespace pvtap::analyzer
