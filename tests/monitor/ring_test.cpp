#include "smart/monitor/ring.hpp"

#include <gtest/gtest.h>

#include <string>

namespace smart::monitor {
namespace {

TEST(Ring, KeepsQueueOrderAcrossWrapAndGrowth) {
  Ring<int> q;
  int next_in = 0, next_out = 0;
  // Push three, pop two, many times: the front wraps around the slots and storage grows while
  // the queue wraps.
  for (int round = 0; round < 40; ++round) {
    for (int k = 0; k < 3; ++k) q.push_back() = next_in++;
    for (int k = 0; k < 2; ++k) {
      ASSERT_EQ(q.front(), next_out++);
      q.pop_front();
    }
    for (std::size_t i = 0; i < q.size(); ++i) ASSERT_EQ(q[i], next_out + int(i));
  }
  EXPECT_EQ(q.size(), 40u);
  EXPECT_EQ(q.capacity(), 64u);
}

TEST(Ring, PopBackDropsTheNewest) {
  Ring<int> q;
  for (int k = 0; k < 5; ++k) q.push_back() = k;
  q.pop_back();
  q.pop_back();
  ASSERT_EQ(q.size(), 3u);
  EXPECT_EQ(q.back(), 2);
  q.push_back() = 7;
  EXPECT_EQ(q[3], 7);
}

TEST(Ring, ReusesAPoppedSlotWithItsStorage) {
  Ring<std::string> q;
  q.reserve(8);
  for (int k = 0; k < 8; ++k) q.push_back() = std::string(100, char('a' + k));
  const char* storage = q.front().data();
  for (int k = 0; k < 8; ++k) q.pop_front();
  EXPECT_TRUE(q.empty());
  // Eight pushes come round to the first slot again: its string is handed back as it was left.
  for (int k = 0; k < 8; ++k) q.push_back();
  EXPECT_EQ(q.capacity(), 8u);
  EXPECT_EQ(q.front(), std::string(100, 'a'));
  EXPECT_EQ(q.front().data(), storage);
}

TEST(Ring, ReserveNeverMovesWhatFits) {
  Ring<int> q;
  q.reserve(20);
  EXPECT_EQ(q.capacity(), 32u);
  q.reserve(10);
  EXPECT_EQ(q.capacity(), 32u);
}

}  // namespace
}  // namespace smart::monitor
