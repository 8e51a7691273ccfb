#include "smart/agent/action_queue.hpp"

#include <gtest/gtest.h>

namespace smart::agent {
namespace {

std::vector<AgentAction> window(uint32_t first, uint32_t last) {
  std::vector<AgentAction> w;
  for (uint32_t s = first; s <= last; ++s) w.push_back({s, ActionKind::kMove, 0, 0, 0, 0, 0});
  return w;
}

std::vector<uint32_t> seqs(const ActionQueue& q) {
  std::vector<uint32_t> out;
  for (const auto& a : q.pending()) out.push_back(a.seq);
  return out;
}

TEST(ActionQueue, RepeatedOverlappingAndOlderWindowsChangeNothing) {
  ActionQueue q;
  using R = ActionQueue::Result;
  EXPECT_EQ(q.apply(10, window(0, 3)), R::kAccepted);
  EXPECT_EQ(q.apply(10, window(0, 3)), R::kUnchanged);
  EXPECT_EQ(q.apply(10, window(0, 1)), R::kUnchanged);
  EXPECT_EQ(q.apply(10, window(2, 5)), R::kAccepted);
  EXPECT_EQ(seqs(q), (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
  q.finish_front();
  q.finish_front();
  EXPECT_EQ(q.finished_seq(), 1);
  EXPECT_EQ(q.apply(10, window(0, 5)), R::kUnchanged);  // late duplicate of an old window
  EXPECT_EQ(seqs(q), (std::vector<uint32_t>{2, 3, 4, 5}));
  EXPECT_GT(q.duplicates_ignored(), 0u);
}

TEST(ActionQueue, GapsAreNotSkipped) {
  ActionQueue q;
  q.apply(1, window(0, 1));
  EXPECT_EQ(q.apply(1, window(4, 6)), ActionQueue::Result::kGap);
  EXPECT_EQ(seqs(q), (std::vector<uint32_t>{0, 1}));
}

TEST(ActionQueue, NewerRunRestartsOlderRunIsIgnored) {
  ActionQueue q;
  q.apply(5, window(0, 2));
  EXPECT_EQ(q.apply(4, window(0, 9)), ActionQueue::Result::kStaleRun);
  EXPECT_EQ(q.apply(6, window(7, 8)), ActionQueue::Result::kAccepted);
  EXPECT_EQ(q.run_id(), 6u);
  EXPECT_EQ(q.finished_seq(), 6);  // a restarted agent resumes where the monitor says
  EXPECT_EQ(seqs(q), (std::vector<uint32_t>{7, 8}));
}

}  // namespace
}  // namespace smart::agent
