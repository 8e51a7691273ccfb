// PipePlanner with real child processes: the example Python planner, and tiny fake planners (a
// Python file each, written by the test) that break one rule each.
#include "smart/tools/pipe_planner.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "smart/lifelong/plan_protocol.hpp"

namespace smart::tools {
namespace {

namespace fs = std::filesystem;

// 4 x 3, an obstacle at (1, 1); two robots, windows of two steps.
grid::Grid small_map() {
  std::vector<uint8_t> blocked(12, 0);
  blocked[1 * 4 + 1] = 1;
  return {4, 3, blocked};
}

planning::WindowRequest request() { return {{{0, 0}, {3, 0}}, {{{3, 2}}, {{0, 2}}}, 2}; }

class PipePlannerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("smart_pipe_planner_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A planner whose reply to a request `m` is the Python expression `reply` (a str, or None for
  // no reply); `before` runs first (e.g. a sleep).
  std::string fake(const std::string& reply, const std::string& before = "pass") {
    const auto file = dir_ / "planner.py";
    std::ofstream(file)
        << "import json, sys, time\n"
           "for line in sys.stdin:\n"
           "    m = json.loads(line)\n"
           "    if m['type'] == 'start':\n"
           "        print(json.dumps({'type': 'ready', 'name': 'fake'}), flush=True)\n"
           "        continue\n"
           "    w = m['window']\n"
        << "    " << before << "\n"
        << "    r = " << reply << "\n"
        << "    if r is not None:\n"
           "        print(r, flush=True)\n";
    return "python3 " + file.string();
  }

  lifelong::PlannedWindow plan(PipePlanner& p) {
    p.submit(request());
    auto w = p.poll();
    EXPECT_TRUE(w.has_value());
    return w.value_or(lifelong::PlannedWindow{});
  }

  grid::Grid grid_ = small_map();
  fs::path dir_;
};

// A reply with the paths given (Python list text), for window w.
std::string paths(const std::string& list) {
  return "json.dumps({'window': w, 'paths': " + list + "})";
}

TEST_F(PipePlannerTest, TheExamplePythonPlannerPlansValidWindows) {
  PipePlanner p(grid_, 2, 2,
                {"python3 " SMART_SOURCE_DIR "/examples/planners/greedy_planner.py", 30, 0.1, 0});
  for (int k = 0; k < 3; ++k) {
    const auto w = plan(p);
    ASSERT_EQ(w.error, "");
    EXPECT_EQ(lifelong::check_window(grid_, request(), w.paths), "");
    EXPECT_NE(w.paths[0][2], (grid::Cell{0, 0}));  // it moves toward its errand
  }
}

TEST_F(PipePlannerTest, AWindowThatBreaksARuleIsRefusedWithTheRule) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"[[[0,0],[1,0],[2,0]], [[3,0],[2,0],[2,0]]]", "robots 0 and 1 collide at (x=2,y=0)"},
      {"[[[0,0],[0,2],[0,2]], [[3,0],[3,0],[3,0]]]", "robot 0 step 1 jumps"},
      {"[[[0,0],[-1,0],[0,0]], [[3,0],[3,0],[3,0]]]", "robot 0 step 1 leaves the map"},
      {"[[[0,1],[0,2],[0,2]], [[3,0],[3,0],[3,0]]]", "robot 0 starts at (x=0,y=1), not at its cut"},
  };
  for (const auto& [list, why] : cases) {
    PipePlanner p(grid_, 2, 2, {fake(paths(list)), 30, 0, 0});
    const auto w = plan(p);
    EXPECT_NE(w.error.find("--planner-cmd window 1 refused: " + why), std::string::npos)
        << list << " -> " << w.error;
    EXPECT_TRUE(w.paths.empty());
  }
}

TEST_F(PipePlannerTest, AMalformedReplyIsRefusedAndTheNextWindowStillPlanned) {
  PipePlanner p(grid_, 2, 2,
                {fake("'{oops' if w == 1 else " + paths("[[[0,0]]*3, [[3,0]]*3]")), 30, 0, 0});
  EXPECT_NE(plan(p).error.find("malformed reply: not JSON"), std::string::npos);
  EXPECT_EQ(plan(p).error, "");
}

TEST_F(PipePlannerTest, ThePlannersOwnErrorIsTheReason) {
  PipePlanner p(grid_, 2, 2, {fake("json.dumps({'window': w, 'error': 'no idea'})"), 30, 0, 0});
  EXPECT_NE(plan(p).error.find("the planner could not plan: no idea"), std::string::npos);
}

// Window 1's reply comes after its deadline; window 2's request finds it first in the pipe and
// skips it as stale. The planner is told when it may answer by a file the test creates (no
// guessed times): it waits for the file before answering window 1.
TEST_F(PipePlannerTest, ALateReplyIsRefusedAndSkippedWhenItComes) {
  const auto gate = dir_ / "gate";
  const std::string wait_gate = "while w == 1 and not __import__('os').path.exists('" +
                                gate.string() + "'): time.sleep(0.01)";
  PipePlanner p(grid_, 2, 2, {fake(paths("[[[0,0]]*3, [[3,0]]*3]"), wait_gate), 0.2, 0, 0});
  const auto late = plan(p);
  EXPECT_NE(late.error.find("late: no reply within 0.2 s (--planner-timeout-s)"), std::string::npos)
      << late.error;
  std::ofstream(gate) << "go";
  // Window 2: the planner answers window 1 (stale, skipped), then window 2. A loaded machine may
  // take longer than 0.2 s for both: then window 2 is late too, and window 3 is answered.
  std::string error = "not planned";
  for (int k = 0; k < 50 && !error.empty(); ++k) error = plan(p).error;
  EXPECT_EQ(error, "");
}

TEST_F(PipePlannerTest, AHungPlannerIsLateEveryWindowAndNeverBlocksLonger) {
  PipePlanner p(grid_, 2, 2, {fake("None"), 0.05, 0, 0});  // reads requests, never answers
  for (int k = 0; k < 3; ++k) {
    EXPECT_NE(plan(p).error.find("late: no reply within 0.05 s"), std::string::npos);
  }
}

// Regression: a whole number of seconds was written "2. s".
TEST_F(PipePlannerTest, AWholeTimeoutIsWrittenAsAWholeNumber) {
  PipePlanner p(grid_, 2, 2, {fake("None"), 1, 0, 0});
  EXPECT_NE(plan(p).error.find("late: no reply within 1 s (--planner-timeout-s)"),
            std::string::npos);
}

TEST_F(PipePlannerTest, APlannerThatStopsReadingIsRefusedForGood) {
  // Reads the start line, then sleeps: requests fill the pipe until one cannot be written.
  const auto file = dir_ / "sleeper.py";
  std::ofstream(file) << "import sys, time\nsys.stdin.readline()\n"
                         "print('{\"type\": \"ready\"}', flush=True)\ntime.sleep(60)\n";
  grid::Grid wide(400, 400, std::vector<uint8_t>(160000, 0));
  std::vector<grid::Cell> starts;
  starts.reserve(4000);
  for (int32_t k = 0; k < 4000; ++k) starts.push_back({k % 400, k / 400});
  PipePlanner p(wide, starts.size(), 2, {"python3 " + file.string(), 0.2, 0, 0});
  std::string error;
  for (int k = 0; k < 20 && error.find("stopped reading") == std::string::npos; ++k) {
    p.submit({starts, std::vector<std::vector<grid::Cell>>(starts.size()), 2});
    error = p.poll()->error;
  }
  EXPECT_NE(error.find("the planner stopped reading its input"), std::string::npos) << error;
  p.submit({starts, std::vector<std::vector<grid::Cell>>(starts.size()), 2});
  EXPECT_NE(p.poll()->error.find("stopped reading"), std::string::npos);
}

TEST_F(PipePlannerTest, ACrashedPlannerIsRefusedAtOnceForEveryLaterWindow) {
  PipePlanner p(grid_, 2, 2, {fake("sys.exit(3)"), 30, 0, 0});
  const auto first = plan(p);
  EXPECT_NE(first.error.find("the planner closed its output and exited with code 3"),
            std::string::npos)
      << first.error;
  const auto second = plan(p);
  EXPECT_NE(second.error.find("no more windows from it"), std::string::npos);
  EXPECT_LT(second.wall_ms, 1000);
}

TEST_F(PipePlannerTest, AFloodOfLinesIsBoundedAndEndsLate) {
  // For each request: a reply far longer than the bound, then stale replies without end.
  PipePlanner p(grid_, 2, 2,
                {fake("None",
                      "print('x' * 100000, flush=True)\n"
                      "    while True: print('{\"window\": 0}', flush=True)") +
                     " 2>/dev/null",  // its broken pipe when the test ends
                 0.3, 0, 4096});
  EXPECT_NE(plan(p).error.find("a reply longer than 4096 bytes was dropped"), std::string::npos);
  EXPECT_NE(plan(p).error.find("late"), std::string::npos);
}

TEST_F(PipePlannerTest, ACommandThatExitsAtOnceIsAnErrorNamingIt) {
  try {
    PipePlanner p(grid_, 2, 2, {"exit 4", 5, 0, 0});
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "--planner-cmd 'exit 4' exited before it was ready (exit code 4)"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(PipePlannerTest, APlannerThatIsNotReadyIsAnErrorSayingWhatWasExpected) {
  try {
    PipePlanner p(grid_, 2, 2, {"read x; echo hello; sleep 30", 5, 0, 0});
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the first line a planner writes is {\"type\": "
                                         "\"ready\"} once it has read the start line; it "
                                         "wrote: hello"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(PipePlannerTest, TheReadyLineNamesThePlanner) {
  PipePlanner p(grid_, 2, 2, {fake("None"), 0.05, 0, 0});
  EXPECT_EQ(p.name(), "fake");
  EXPECT_EQ(plan(p).heuristic, "external: fake");
}

}  // namespace
}  // namespace smart::tools
