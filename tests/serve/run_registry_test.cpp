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

}  // namespace
}  // namespace smart::serve
