// The chunk timeline's queue: first in, first out across wrap-arounds and growth, and told
// when its elements moved.
#include "../../../protocols/src/framing/ring_buffer.h"

#include <gtest/gtest.h>

#include <deque>

namespace pvtap::detail {
namespace {

TEST(RingBuffer, BehavesAsADequeUsedAsAQueue) {
  RingBuffer<int> ring;
  std::deque<int> reference;
  int next = 0;
  // Pushes outrun pops for a while (growth), then pops catch up (wrap-around), many times.
  for (int round = 0; round < 200; ++round) {
    const int pushes = round % 7 == 0 ? 40 : 3;
    for (int i = 0; i < pushes; ++i) {
      const int* before = ring.empty() ? nullptr : &ring.front();
      const bool moved = ring.push_back(next);
      reference.push_back(next++);
      if (before != nullptr && !moved) {
        EXPECT_EQ(before, &ring.front());  // elements stay where they are
      }
    }
    const int pops = round % 5 == 0 ? static_cast<int>(reference.size()) - 1 : 3;
    for (int i = 0; i < pops && reference.size() > 1; ++i) {
      ring.pop_front();
      reference.pop_front();
    }
    ASSERT_EQ(ring.size(), reference.size());
    for (std::size_t i = 0; i < reference.size(); ++i) ASSERT_EQ(ring[i], reference[i]) << i;
    EXPECT_EQ(ring.front(), reference.front());
    EXPECT_EQ(ring.back(), reference.back());
  }
}

TEST(RingBuffer, GrowingIsReportedOnlyWhenFull) {
  RingBuffer<int> ring;
  EXPECT_TRUE(ring.push_back(1));  // the first array
  int moves = 0;
  for (int i = 0; i < 1000; ++i) moves += ring.push_back(i) ? 1 : 0;
  EXPECT_EQ(moves, 6);  // 16 -> 32 -> ... -> 1024
  for (int i = 0; i < 1000; ++i) {
    ring.pop_front();
    EXPECT_FALSE(ring.push_back(i));  // a steady queue never moves again
  }
}

}  // namespace
}  // namespace pvtap::detail
