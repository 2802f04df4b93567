// MarkedBytes: a tty's PARMRK escapes read back into bytes and errors, whatever the read cuts.
#include "serial/marked_bytes.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace pvtap::analyzer {
namespace {

std::vector<LineByte> unmark_in_pieces(const std::vector<std::uint8_t>& in, std::size_t piece) {
  MarkedBytes marks;
  std::vector<LineByte> out;
  for (std::size_t i = 0; i < in.size(); i += piece) {
    const std::size_t n = std::min(piece, in.size() - i);
    marks.unmark(std::span(in).subspan(i, n), out);
  }
  return out;
}

TEST(MarkedBytes, ErrorsEscapedBytesAndBreaks) {
  // 0x11, 0x41 with a framing error, a real 0xFF, a break (or 0x00 with an error), 0x22.
  const std::vector<std::uint8_t> in{0x11, 0xFF, 0x00, 0x41, 0xFF, 0xFF, 0xFF, 0x00, 0x00, 0x22};
  for (std::size_t piece = 1; piece <= in.size(); ++piece) {
    SCOPED_TRACE(piece);
    const std::vector<LineByte> out = unmark_in_pieces(in, piece);
    ASSERT_EQ(out.size(), 5u);
    const std::uint8_t values[] = {0x11, 0x41, 0xFF, 0x00, 0x22};
    const bool errors[] = {false, true, false, true, false};
    for (std::size_t k = 0; k < out.size(); ++k) {
      EXPECT_EQ(out[k].value, values[k]) << k;
      EXPECT_EQ(out[k].error, errors[k]) << k;
    }
  }
}

TEST(MarkedBytes, AStray377IsKept) {
  const std::vector<LineByte> out = unmark_in_pieces({0xFF, 0x42}, 2);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].value, 0xFF);
  EXPECT_EQ(out[1].value, 0x42);
}

}  // namespace
}  // namespace pvtap::analyzer
