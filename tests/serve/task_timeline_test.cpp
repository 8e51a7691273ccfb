// serve/task_timeline.hpp: a lifelong run's tasks.csv, events.csv and throughput.csv as the
// viewer's task timeline; malformed files are named, stray events skipped.
#include "smart/serve/task_timeline.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "smart/monitor/results_format.hpp"

namespace smart::serve {
namespace {

using ::testing::HasSubstr;

std::string tasks_csv() {
  std::string t(results::kTasksHeader);
  t += '\n';
  results::append_row(t, {4, 1, 2u, 2, 2, 0.5, 1.0, 3.0, 7.5, {{1, 2}, {5, 0}}});
  results::append_row(
      t, {5, 0, std::nullopt, 1, 0, 2.0, std::nullopt, std::nullopt, std::nullopt, {{3, 3}}});
  return t;
}

std::string events_csv() {
  std::string e(results::kEventsHeader);
  e += '\n';
  for (const auto& row : {results::EventRow{1.0, "assigned", 4, 2u, std::nullopt, ""},
                          results::EventRow{3.0, "opened", 4, 2u, 0u, ""},
                          results::EventRow{7.5, "finished", 4, 2u, 1u, ""},
                          results::EventRow{8.0, "errand", 9, 1u, 0u, ""},  // no such task
                          results::EventRow{8.5, "errand", 5, 1u, 3u, ""},  // past its errands
                          results::EventRow{9.0, "refused", std::nullopt, std::nullopt,
                                            std::nullopt, "late, by 2 s"}}) {
    results::append_row(e, row);
  }
  return e;
}

TEST(TaskTimeline, EveryTaskWithItsCellsRobotTimesAndErrandsDone) {
  std::string thr(results::kThroughputHeader);
  thr += '\n';
  results::append_row(thr, results::ThroughputRow{1, 0, 0, 2.5, 10, 1});
  results::append_row(thr, results::ThroughputRow{8, 1, 1, 2.0, 10, 0});
  const auto j = task_timeline(tasks_csv(), events_csv(), thr);
  ASSERT_EQ(j["tasks"].size(), 2u);
  const auto& t4 = j["tasks"][0];
  EXPECT_EQ(t4["id"], 4);
  EXPECT_EQ(t4["robot"], 2);
  EXPECT_EQ(t4["cells"], nlohmann::json::parse("[[1, 2], [5, 0]]"));
  EXPECT_EQ(t4["done_s"], nlohmann::json::parse("[3.0, 7.5]"));
  EXPECT_EQ(t4["finished_s"], 7.5);
  const auto& t5 = j["tasks"][1];
  EXPECT_TRUE(t5["robot"].is_null());
  EXPECT_TRUE(t5["assigned_s"].is_null());
  EXPECT_EQ(t5["done_s"], nlohmann::json::array());  // the errand past its cells is skipped
  EXPECT_EQ(j["throughput"]["t_s"], nlohmann::json::parse("[1.0, 8.0]"));
  EXPECT_EQ(j["throughput"]["finished"], nlohmann::json::parse("[0, 1]"));
  EXPECT_EQ(j["throughput"]["last_min"], nlohmann::json::parse("[0, 1]"));
}

// A running run: tasks.csv has none of its open tasks yet; events.csv tells them, their cells
// with the revealed event.
TEST(TaskTimeline, ARunningRunsTasksComeFromItsEvents) {
  std::string e(results::kEventsHeader);
  e += '\n';
  for (const auto& row :
       {results::EventRow{0, "revealed", 1, std::nullopt, std::nullopt, "2 3;4 5"},
        results::EventRow{0, "revealed", 2, std::nullopt, std::nullopt, "7 7"},
        results::EventRow{0.5, "assigned", 1, 6u, std::nullopt, ""},
        results::EventRow{2.0, "opened", 1, 6u, 0u, ""},
        results::EventRow{3.0, "revealed", 3, std::nullopt, std::nullopt, "x"}}) {
    results::append_row(e, row);
  }
  std::string header(results::kTasksHeader);
  const auto j = task_timeline(header + "\n", e, "");
  ASSERT_EQ(j["tasks"].size(), 2u);  // task 3's cells are malformed: not drawn
  EXPECT_EQ(j["tasks"][0]["robot"], 6);
  EXPECT_EQ(j["tasks"][0]["assigned_s"], 0.5);
  EXPECT_EQ(j["tasks"][0]["cells"], nlohmann::json::parse("[[2, 3], [4, 5]]"));
  EXPECT_EQ(j["tasks"][0]["done_s"], nlohmann::json::parse("[2.0]"));
  EXPECT_TRUE(j["tasks"][0]["finished_s"].is_null());
  EXPECT_TRUE(j["tasks"][1]["robot"].is_null());
}

TEST(TaskTimeline, AMalformedFileIsNamedWithItsLine) {
  EXPECT_THAT([] { (void)task_timeline(tasks_csv() + "x,y\n", "", ""); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("tasks.csv line 4")));
  EXPECT_THAT([] { (void)task_timeline(tasks_csv(), events_csv() + "nan,opened,,,,\n", ""); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("events.csv line 8")));
  const auto j = task_timeline(tasks_csv(), "", "");  // files the run did not write yet
  EXPECT_EQ(j["tasks"].size(), 2u);
  EXPECT_TRUE(j["throughput"]["t_s"].empty());
}

}  // namespace
}  // namespace smart::serve
