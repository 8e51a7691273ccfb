// RobotSet (robot_set.hpp): robots taken smallest first, across words and summary words, as a
// set of ids; checked against std::set on seeded random operations.
#include "smart/monitor/robot_set.hpp"

#include <gtest/gtest.h>

#include <random>
#include <set>

namespace smart::monitor {
namespace {

TEST(RobotSet, TakesTheSmallestFirstAcrossWords) {
  RobotSet s(5000);  // two summary words
  EXPECT_TRUE(s.none());
  EXPECT_EQ(s.take_first(), RobotSet::kNone);
  for (const uint32_t r : {4999u, 64u, 4096u, 63u, 0u}) s.set(r);
  EXPECT_TRUE(s.any());
  EXPECT_TRUE(s.test(4096));
  EXPECT_FALSE(s.test(65));
  for (const uint32_t r : {0u, 63u, 64u, 4096u, 4999u}) EXPECT_EQ(s.take_first(), r);
  EXPECT_TRUE(s.none());
}

TEST(RobotSet, AWordEmptiedIsSkipped) {
  RobotSet s(200);
  s.set(3);
  s.set(130);
  s.reset(3);
  EXPECT_TRUE(s.any());
  EXPECT_EQ(s.first(), 130u);
  s.reset(130);
  EXPECT_FALSE(s.any());
  s.reset(130);  // not in the set: nothing changes
  EXPECT_FALSE(s.any());
}

TEST(RobotSet, UnionAndClear) {
  RobotSet a(300), b(300);
  a.set(200);
  b.set(5);
  b.set(299);
  a |= b;
  EXPECT_TRUE(b.test(5));  // b is read, not changed
  EXPECT_EQ(a.take_first(), 5u);
  EXPECT_EQ(a.take_first(), 200u);
  EXPECT_EQ(a.take_first(), 299u);
  a.set(7);
  a.clear();
  EXPECT_TRUE(a.none());
  EXPECT_FALSE(a.test(7));
  a.set(8);
  EXPECT_EQ(a.take_first(), 8u);
}

// Random sets, unions and takes against std::set, sizes around the word and summary edges.
TEST(RobotSet, AgreesWithAnOrderedSet) {
  std::mt19937 rng(7);
  for (const uint32_t size : {1u, 63u, 64u, 65u, 1000u, 4096u, 4097u, 10000u}) {
    RobotSet s(size), other(size);
    std::set<uint32_t> model, other_model;
    std::uniform_int_distribution<uint32_t> robot(0, size - 1), op(0, 9);
    for (int step = 0; step < 4000; ++step) {
      const uint32_t r = robot(rng);
      switch (op(rng)) {
        case 0:
        case 1:
        case 2:
        case 3:
          s.set(r);
          model.insert(r);
          break;
        case 4:
        case 5:
          s.reset(r);
          model.erase(r);
          break;
        case 6:
          other.set(r);
          other_model.insert(r);
          break;
        case 7:
          s |= other;
          model.insert(other_model.begin(), other_model.end());
          break;
        case 8: {
          const uint32_t got = s.take_first();
          if (model.empty()) {
            ASSERT_EQ(got, RobotSet::kNone);
          } else {
            ASSERT_EQ(got, *model.begin()) << "size " << size << " step " << step;
            model.erase(model.begin());
          }
          break;
        }
        default:
          if (step % 50 == 0) {
            s.clear();
            model.clear();
          }
      }
      ASSERT_EQ(s.any(), !model.empty()) << "size " << size << " step " << step;
      ASSERT_EQ(s.test(r), model.count(r) == 1) << "size " << size << " step " << step;
    }
  }
}

}  // namespace
}  // namespace smart::monitor
