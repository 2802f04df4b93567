// Result: a value or its diagnostics, as the map loader and the frame codec return them.
#include "pvtap/codec/result.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hex_bytes.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/registers/register_map.h"

namespace pvtap {
namespace {

TEST(Result, HoldsAValueOrItsDiagnostics) {
  const Result<int> good = 7;
  ASSERT_TRUE(good.ok());
  EXPECT_TRUE(static_cast<bool>(good));
  EXPECT_EQ(good.value(), 7);
  EXPECT_TRUE(good.diagnostics().empty());

  const auto bad = Result<int>::failure("not a number");
  EXPECT_FALSE(bad.ok());
  EXPECT_EQ(bad.diagnostics(), "not a number");
  EXPECT_EQ(bad.error_text(), "not a number");
}

TEST(Result, AFrameThatDoesNotParseSaysWhy) {
  const ParseOutcome short_frame =
      parse_frame(test::hex_bytes("01 03 00"), Dialect::Gsl, Role::Request);
  EXPECT_FALSE(short_frame);
  EXPECT_EQ(short_frame.error_text(), "RTU frame shorter than 4 bytes");
  const ParseOutcome good =
      parse_frame(test::hex_bytes("01 03 00 00 00 0A C5 CD"), Dialect::Gsl, Role::Request);
  ASSERT_TRUE(good);
  EXPECT_EQ(good->count, 10);
}

TEST(Result, AMapThatDoesNotLoadListsItsProblemsOnePerLine) {
  const RegisterMapResult map = load_register_map("dialect = \"nope\"\n", "bad.toml");
  ASSERT_FALSE(map);
  ASSERT_FALSE(map.diagnostics().empty());
  std::string lines;
  for (const MapDiagnostic& d : map.diagnostics()) {
    if (!lines.empty()) lines += '\n';
    lines += d.to_string();
  }
  EXPECT_EQ(map.error_text(), lines);
  EXPECT_NE(map.error_text().find("bad.toml"), std::string::npos);
}

}  // namespace
}  // namespace pvtap
