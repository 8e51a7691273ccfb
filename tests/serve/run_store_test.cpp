// The run store on a real temporary data folder, with real child processes standing in for
// `smart run` (a shell that writes a summary, or fails).
#include "smart/serve/run_store.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <thread>

namespace smart::serve {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("smart-run-store-" + std::to_string(::getpid()) +
                                               "-" + std::to_string(counter++));
  static inline int counter = 0;
  ~TempDir() { fs::remove_all(path); }
};

// Tends the store until the run has ended (each check is an event: the child's exit).
RunEntry ended(RunStore& store, const std::string& id) {
  for (int i = 0; i < 3000; ++i) {
    store.tend(1);
    const auto e = store.entry(id);
    if (e && (e->state == RunState::kDone || e->state == RunState::kFailed)) return *e;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ADD_FAILURE() << id << " never ended";
  return {};
}

TEST(RunStore, AStagedUploadBecomesARunWholeAndItsCommandRunsThere) {
  TempDir d;
  RunStore store(d.path);
  const auto staged = store.stage();
  ASSERT_TRUE(fs::is_directory(staged));
  std::ofstream(staged / "map.map") << "map";
  const auto id = store.add_queued(staged, "warehouse.map", 3, [&](const std::string& run) {
    const auto results = store.dir(run) / "results";
    return std::vector<std::string>{
        "/bin/sh", "-c",
        "mkdir -p " + results.string() + " && echo '{}' > " + (results / "summary.json").string()};
  });
  EXPECT_FALSE(fs::exists(staged)) << "renamed, not copied";
  EXPECT_TRUE(fs::exists(store.dir(id) / "map.map"));
  EXPECT_EQ(store.entry(id)->state, RunState::kQueued);
  const auto e = ended(store, id);
  EXPECT_EQ(e.state, RunState::kDone) << e.error;
  EXPECT_EQ(e.map_name, "warehouse.map");
  EXPECT_EQ(store.list().size(), 1u);
}

TEST(RunStore, ARunThatFailsIsRecordedNamingItsOutput) {
  TempDir d;
  RunStore store(d.path);
  const auto id = store.add_queued(store.stage(), "m", 1, [](const std::string&) {
    return std::vector<std::string>{"/bin/sh", "-c", "echo broken; exit 3"};
  });
  const auto e = ended(store, id);
  EXPECT_EQ(e.state, RunState::kFailed);
  EXPECT_THAT(e.error, HasSubstr("exited with code 3"));
  EXPECT_THAT(e.error, HasSubstr((store.dir(id) / "run.out").string()));
}

TEST(RunStore, AReplayIsDoneAtOnceAndOnlyRunIdsNameRuns) {
  TempDir d;
  RunStore store(d.path);
  const auto id = store.add_done(store.stage(), "replay.map", 5);
  EXPECT_EQ(store.entry(id)->state, RunState::kDone);
  EXPECT_EQ(store.results_file(id, "robots.csv"), store.dir(id) / "results" / "robots.csv");
  EXPECT_FALSE(store.entry("../" + id).has_value());
  EXPECT_FALSE(store.entry("upload-1").has_value()) << "a staging folder is not a run";
}

// Issue 26: a restarted `smart serve` listed none of the old runs, its first upload failed on an
// existing folder, and two servers shared one data folder. The store locks its folder, adopts
// what a previous store left (a finished replay done, a run cut off failed as interrupted),
// removes half-written uploads, skips what is not a run, and never reuses a name.
TEST(RunStore, ARestartedStoreAdoptsTheRunsContinuesTheIdsAndLocksTheFolder) {
  TempDir d;
  std::string done_id;
  {
    RunStore store(d.path);
    EXPECT_THROW(RunStore second(d.path), std::runtime_error);  // one server per data folder
    const auto staged = store.stage();
    fs::create_directories(staged / "results");
    std::ofstream(staged / "results" / "summary.json") << "{}";
    done_id = store.add_done(staged, "warehouse.map", 12);
    const auto cut = store.stage();
    store.add_queued(cut, "cut.map", 3, [](const std::string&) {
      return std::vector<std::string>{"/bin/sleep", "600"};
    });
    store.tend(1);  // it runs; the store ends under it
  }
  fs::create_directories(d.path / "upload-9" / "results");       // a half-written upload
  std::ofstream(d.path / "run-000005") << "not a folder";        // a surprise
  fs::create_directories(d.path / "run-000004");                 // no entry.json
  std::ofstream(d.path / "run-000004" / "entry.json") << "[[[";  // and a damaged one
  RunStore store(d.path);
  const auto runs = store.list();
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0].id, done_id);
  EXPECT_EQ(runs[0].state, RunState::kDone);
  EXPECT_EQ(runs[0].map_name, "warehouse.map");
  EXPECT_EQ(runs[0].robots, 12u);
  EXPECT_EQ(runs[1].state, RunState::kFailed);
  EXPECT_THAT(runs[1].error, HasSubstr("interrupted"));
  EXPECT_EQ(runs[2].id, "run-000004");
  EXPECT_FALSE(fs::exists(d.path / "upload-9"));
  const auto staged = store.stage();
  fs::create_directories(staged / "results");
  const auto next = store.add_done(staged, "next.map", 1);
  EXPECT_EQ(next, "run-000006");  // after the largest run folder; run-000005 is someone's file
  EXPECT_TRUE(fs::is_directory(d.path / next));
  EXPECT_EQ(store.entry(next)->state, RunState::kDone);
}

// A run whose command cannot start (its program gone, the process table full) threw out of the
// tending loop and ended the server (terminate, exit 134). It fails alone, saying why.
TEST(RunStore, ARunThatCannotStartFailsAloneNamingWhy) {
  TempDir d;
  RunStore store(d.path);
  const auto id = store.add_queued(store.stage(), "m.map", 1, [](const std::string&) {
    return std::vector<std::string>{"/nonexistent/smart", "run"};
  });
  EXPECT_NO_THROW(store.tend(1));
  const auto e = store.entry(id);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->state, RunState::kFailed);
  EXPECT_THAT(e->error, HasSubstr("could not start: cannot start '/nonexistent/smart'"));
}

}  // namespace
}  // namespace smart::serve
