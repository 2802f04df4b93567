// BusCounters and ReassemblerTotals add up every counter they hold.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "pvtap/framing/stream_reassembler.h"
#include "pvtap/session/bus_report.h"

namespace pvtap {
namespace {

// Every field is a 64-bit counter: set them all through their bytes, so that a counter
// that operator+= forgets shows up whatever its name.
template <typename Counters>
void expect_every_counter_added() {
  static_assert(std::is_trivially_copyable_v<Counters>);
  constexpr std::size_t n = sizeof(Counters) / sizeof(std::uint64_t);
  std::array<std::uint64_t, n> a_fields{};
  std::array<std::uint64_t, n> b_fields{};
  for (std::size_t i = 0; i < n; ++i) {
    a_fields[i] = i + 1;
    b_fields[i] = 1000 * (i + 1);
  }
  Counters a;
  Counters b;
  std::memcpy(static_cast<void*>(&a), a_fields.data(), sizeof a);
  std::memcpy(static_cast<void*>(&b), b_fields.data(), sizeof b);
  a += b;
  std::array<std::uint64_t, n> sum{};
  std::memcpy(sum.data(), &a, sizeof a);
  for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(sum[i], 1001 * (i + 1)) << "counter " << i;
}

TEST(BusCounters, AddingUpCoversEveryCounter) {
  expect_every_counter_added<BusCounters>();
}

TEST(ReassemblerTotals, AddingUpCoversEveryCounter) {
  expect_every_counter_added<ReassemblerTotals>();
}

TEST(BusCounters, AReportAddsUpAsItsCounters) {
  BusReport a;
  a.requests = 2;
  a.bytes.frames = 3;
  a.gaps.lost_bytes = 7;
  BusReport b;
  b.requests = 5;
  b.bytes.frames = 1;
  b.by_dialect[1].responses = 4;
  a.counters() += b.counters();
  EXPECT_EQ(a.requests, 7u);
  EXPECT_EQ(a.bytes.frames, 4u);
  EXPECT_EQ(a.gaps.lost_bytes, 7u);
  EXPECT_EQ(a.by_dialect[1].responses, 4u);
}

}  // namespace
}  // namespace pvtap
