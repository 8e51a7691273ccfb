// Which runs start when, and which ids are accepted from a URL.
#include "smart/serve/run_registry.hpp"

#include <gtest/gtest.h>

namespace smart::serve {
namespace {

TEST(RunRegistry, QueuedRunsStartOldestFirstAtMostMaxRunningAtOnce) {
  RunRegistry r;
  const auto a = r.add("a.map", 10), b = r.add("b.map", 20), c = r.add("c.map", 0);
  EXPECT_EQ(a, "run-000001");
  EXPECT_EQ(r.start_ready(2), (std::vector<std::string>{a, b}));
  EXPECT_TRUE(r.start_ready(2).empty());  // two are running
  r.finish(a, true, "");
  EXPECT_EQ(r.start_ready(2), (std::vector<std::string>{c}));
  r.finish(b, false, "smart run exited with code 3");
  EXPECT_EQ(r.get(a)->state, RunState::kDone);
  EXPECT_EQ(r.get(b)->state, RunState::kFailed);
  EXPECT_EQ(r.get(b)->error, "smart run exited with code 3");
  EXPECT_EQ(r.running(), 1u);
  EXPECT_EQ(r.list().size(), 3u);
  EXPECT_FALSE(r.get("run-000009").has_value());
}

TEST(RunRegistry, OnlyIdsItMakesAreRunIds) {
  EXPECT_TRUE(is_run_id("run-000001"));
  for (const char* bad : {"", "run-", "run-12", "../run-000001", "run-000001/..", "run-00000a",
                          "RUN-000001", "run-000001 "}) {
    EXPECT_FALSE(is_run_id(bad)) << bad;
  }
}

// Issue 26: a restarted server listed none of the old runs and its first upload collided with
// one. Adopted runs are listed as they were and new ids go on after the largest.
TEST(RunRegistry, AdoptedRunsAreListedAndNewIdsGoOnAfterThem) {
  RunRegistry r;
  EXPECT_TRUE(r.adopt({"run-000007", RunState::kDone, {}, "w.map", 100}));
  EXPECT_TRUE(r.adopt({"run-000003", RunState::kFailed, "interrupted", "?", 0}));
  EXPECT_FALSE(r.adopt({"run-000003", RunState::kDone, {}, "again", 1}));  // held already
  EXPECT_FALSE(r.adopt({"../run-000001", RunState::kDone, {}, "x", 1}));
  EXPECT_FALSE(r.adopt({"run-99999999999999999999", RunState::kDone, {}, "x", 1}));
  EXPECT_EQ(r.add("n.map", 5), "run-000008");
  ASSERT_EQ(r.list().size(), 3u);
  EXPECT_EQ(r.list()[0].id, "run-000003");
  EXPECT_EQ(r.get("run-000007")->map_name, "w.map");
  EXPECT_TRUE(r.start_ready(4) == std::vector<std::string>{"run-000008"});  // adopted never rerun
}

}  // namespace
}  // namespace smart::serve
