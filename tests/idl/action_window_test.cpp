#include "smart/dds/action_window.hpp"

#include <gtest/gtest.h>

namespace smart::dds {
namespace {

TEST(ActionWindowBuffer, ViewBorrowsTheStepsWithoutReleasingThem) {
  ActionWindowBuffer w(7, 99, 12);
  for (uint32_t i = 0; i < 3; ++i) {
    smart_msg_ActionStep s{};
    s.seq = 4 + i;
    w.steps().push_back(s);
  }
  const auto& v = w.view();
  EXPECT_EQ(v.robot_id, 7u);
  EXPECT_EQ(v.run_id, 99u);
  EXPECT_EQ(v.total_actions, 12u);
  EXPECT_EQ(v.actions._length, 3u);
  EXPECT_FALSE(v.actions._release);
  EXPECT_EQ(v.actions._buffer, w.steps().data());
  const auto copy = copy_steps(v);
  ASSERT_EQ(copy.size(), 3u);
  EXPECT_EQ(copy[2].seq, 6u);
}

TEST(ActionWindowBuffer, EmptyWindow) {
  ActionWindowBuffer w(1, 2, 0);
  EXPECT_EQ(w.view().actions._length, 0u);
  EXPECT_TRUE(copy_steps(w.view()).empty());
}

}  // namespace
}  // namespace smart::dds
