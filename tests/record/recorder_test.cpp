#include "smart/record/recorder.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "record/mcap_test_reader.hpp"
#include "record_test_files.hpp"

namespace smart::record {
namespace {

using test::get;
using ::testing::HasSubstr;

// Each message's (topic, log time in ms) in file order, from an uncompressed recording.
std::vector<std::pair<std::string, uint64_t>> messages(const std::string& f) {
  std::map<uint16_t, std::string> topics;
  std::vector<std::pair<std::string, uint64_t>> out;
  for (const auto& r : test::walk(f, 8, f.size() - 8)) {
    if (r.op != 0x06) continue;
    const auto comp = get<uint32_t>(r.body, 28);
    const auto size = get<uint64_t>(r.body, 32 + comp);
    const std::string recs = r.body.substr(40 + comp, size);
    for (const auto& m : test::walk(recs, 0, recs.size())) {
      if (m.op == 0x04) {
        const auto len = get<uint32_t>(m.body, 4);
        topics[get<uint16_t>(m.body, 0)] = m.body.substr(8, len);
      } else if (m.op == 0x05) {
        out.emplace_back(topics.at(get<uint16_t>(m.body, 0)), get<uint64_t>(m.body, 6) / 1000000);
      }
    }
  }
  return out;
}

RecorderOptions uncompressed() {
  RecorderOptions o;
  o.mcap.compress = false;
  return o;
}

results::StateRow state(double t, uint32_t r) { return {t, r, 1.0 * r, 2.0, 0.0}; }

TEST(RunRecorder, WritesTheFleetOnceATimeIsCompleteAndProgressOnceStatesPassedIt) {
  StringSink sink;
  auto o = uncompressed();
  o.pose_robots = {1};
  RunRecorder rec(sink, o, 2, 42);
  rec.progress(0.7, 0, 3);  // given before the states, written between 0.5 and 1.0
  rec.progress(0.2, 1, 0);
  for (const double t : {0.5, 1.0}) {
    rec.state(state(t, 0));
    rec.state(state(t, 1));
  }
  rec.finish();
  using P = std::pair<std::string, uint64_t>;
  EXPECT_THAT(messages(sink.bytes()),
              ::testing::ElementsAre(
                  P{"smart/progress", 200}, P{"smart/state", 500}, P{"smart/state", 500},
                  P{"/smart/poses", 500}, P{"/tf", 500}, P{"/robot_1/pose", 500},
                  P{"smart/progress", 700}, P{"smart/state", 1000}, P{"smart/state", 1000},
                  P{"/smart/poses", 1000}, P{"/tf", 1000}, P{"/robot_1/pose", 1000}));
}

TEST(RunRecorder, WritesTheFleetAtMostOncePerPeriod) {
  StringSink sink;
  auto o = uncompressed();
  o.fleet_period_s = 1.0;
  RunRecorder rec(sink, o, 1, 0);
  for (int k = 0; k <= 30; ++k) rec.state(state(0.1 * k, 0));  // 31 times over 3 s
  rec.finish();
  std::vector<uint64_t> fleet;
  for (const auto& [topic, t] : messages(sink.bytes())) {
    if (topic == "/smart/poses") fleet.push_back(t);
  }
  EXPECT_THAT(fleet, ::testing::ElementsAre(0, 1000, 2000, 3000));
}

// A sim clock summed in 0.1 s steps: 0.7 + 0.1 = 0.7999999999999999, 0.8 - 0.7 < 0.1 in doubles.
std::vector<double> summed_clock(int steps) {
  std::vector<double> t{0.0};
  for (int k = 0; k < steps; ++k) t.push_back(t.back() + 0.1);
  return t;
}

std::vector<uint64_t> times_of(const std::string& bytes, const std::string& topic) {
  std::vector<uint64_t> out;
  for (const auto& [name, t] : messages(bytes)) {
    if (name == topic) out.push_back(t);
  }
  return out;
}

TEST(RunRecorder, RegressionFleetWritesWentMissingOnASummedClock) {
  StringSink sink;
  auto o = uncompressed();
  o.fleet_period_s = 0.1;
  RunRecorder rec(sink, o, 1, 0);
  for (const double t : summed_clock(10)) rec.state(state(t, 0));
  rec.finish();
  EXPECT_THAT(times_of(sink.bytes(), "/smart/poses"),
              ::testing::ElementsAre(0, 100, 200, 300, 400, 500, 600, 700, 800, 900, 1000));
}

TEST(RunRecorder, WritesMarkersAtTheFirstFleetAPeriodAfterTheLastAndAtTheEnd) {
  const auto dir = test::fresh_test_dir("smart_recorder_");
  // The plan view's markers need an instance: two robots, one step each.
  const auto in =
      test::corridor_instance(dir, "Agent 0:(1,0,0)->(2,0,1)\nAgent 1:(0,0,0)->(1,0,1)\n");
  StringSink sink;
  auto o = uncompressed();
  o.fleet_period_s = 0.1;
  o.markers_period_s = 1.0;
  RunRecorder rec(sink, o, 2, 0);
  rec.plan_view(in, 1.0, 0.2);
  auto clock = summed_clock(25);  // 0 .. 2.5 s
  // States lost on the way (a keep-last link under load): none from 0.95 to 1.25 s, so the
  // second marker comes at 1.3 s and the third a period after it, not on a 1 s grid.
  std::erase_if(clock, [](double t) { return t > 0.95 && t < 1.25; });
  for (const double t : clock) {
    rec.state(state(t, 0));
    rec.state(state(t, 1));
  }
  rec.finish();
  EXPECT_THAT(times_of(sink.bytes(), "/smart/markers"),
              ::testing::ElementsAre(0, 1300, 2300, 2500));
  std::filesystem::remove_all(dir);
}

TEST(RunRecorder, NamespacesTheRosViewButNotTheRunsOwnTopics) {
  StringSink sink;
  auto o = uncompressed();
  o.ros_namespace = "/run_a";
  RunRecorder rec(sink, o, 1, 0);
  rec.state(state(0, 0));
  rec.finish();
  std::vector<std::string> topics;
  for (const auto& [topic, t] : messages(sink.bytes())) topics.push_back(topic);
  EXPECT_THAT(topics, ::testing::ElementsAre("smart/state", "/run_a/smart/poses", "/run_a/tf"));
}

TEST(RunRecorder, RefusesRobotsOutsideTheFleetAndBadNamespaces) {
  StringSink sink;
  auto o = uncompressed();
  o.pose_robots = {2};
  EXPECT_THROW(RunRecorder(sink, o, 2, 0), std::invalid_argument);
  o.pose_robots = {};
  o.ros_namespace = "/run a";
  EXPECT_THROW(RunRecorder(sink, o, 2, 0), std::invalid_argument);
  o.ros_namespace = "";
  RunRecorder rec(sink, o, 2, 0);
  try {
    rec.state(state(0, 5));
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("robot 5 but the fleet has 2 robots"));
  }
}

}  // namespace
}  // namespace smart::record
