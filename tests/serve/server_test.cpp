// `smart serve` as a user meets it: a real server process on a free loopback port, real runs
// (`smart run` children over DDS), driven with an HTTP client (cpp-httplib).
#include <arpa/inet.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <set>
#include <thread>

#include "smart/serve/recording.hpp"
#include "support/mixed_fleet.hpp"
#include "support/monitor_fixtures.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;
using ::testing::HasSubstr;

class Serve : public ::testing::Test {
 protected:
  void SetUp() override {
    b_ = benchmarks_dir();
    ASSERT_TRUE(std::filesystem::exists(b_)) << smart::test::no_benchmarks(b_);
    data_ = temp_file("serve_data");
    std::filesystem::remove_all(data_);
  }
  // Starts `smart serve` on a free port and waits for the line saying where it listens.
  void start(std::vector<std::string> extra = {}) {
    out_ = temp_file("serve.out");
    std::vector<std::string> args{"serve", "--port", "0", "--data", data_.string()};
    if (std::find(extra.begin(), extra.end(), "--domain") == extra.end()) {
      extra.insert(extra.end(), {"--domain", std::to_string(kServeRuns)});
    }
    args.insert(args.end(), extra.begin(), extra.end());
    server_.emplace(start_smart(args, out_));
    port_ = serve_port(*server_, out_);
    ASSERT_NE(port_, 0) << "smart serve did not say where it listens: " << slurp(out_);
  }
  void TearDown() override {
    server_.reset();
    std::filesystem::remove_all(data_);
  }
  httplib::Result upload(const std::string& plan_file, const std::string& agents,
                         const std::string& real_time_factor = "") {
    httplib::MultipartFormDataItems items{
        {"map", slurp(b_ / "maps/random-32-32-20.map"), "random-32-32-20.map", ""},
        {"scen", slurp(b_ / "scens/random-32-32-20-random-1.scen"), "random.scen", ""},
        {"plan", slurp(plan_file), "paths.txt", ""},
        {"agents", agents, "", ""},
        {"max_speed_mps", "0.75", "", ""},
        {"real_time_factor", real_time_factor, "", ""}};
    return client().Post("/api/runs", items);
  }
  // A loaded machine may take seconds to answer (CI's lint and package builds share 2 cores);
  // httplib's 5 s default read timeout failed an upload there. A long timeout only ends a hang.
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(60, 0);
    c.set_write_timeout(60, 0);
    return c;
  }
  // `smart run --out results` of the 20-robot example's first `agents` robots (a fresh folder).
  SmartRun run_to_folder(const std::filesystem::path& results, const std::string& agents,
                         int domain, const std::string& tag) const {
    std::filesystem::remove_all(results);
    return run_smart(
        {"run", "--map", (b_ / "maps/random-32-32-20.map").string(), "--scen",
         (b_ / "scens/random-32-32-20-random-1.scen").string(), "--plan",
         (b_ / "smart-examples/example_paths_xy.txt").string(), "--axis", "xy", "--agents", agents,
         "--domain", std::to_string(domain), "--out", results.string(), "--no-progress"},
        120s, tag);
  }
  std::filesystem::path b_, data_, out_;
  std::optional<common::ChildProcess> server_;
  int port_ = 0;
};

TEST_F(Serve, AnUploadRunsToCompletionAndItsSummaryAndRecordingAreServed) {
  start();
  // Paced to 100x real time (about 2 s; unpaced it takes about 1 s), as the page's speed choice
  // does to watch a run live.
  const auto posted = upload((b_ / "smart-examples/example_paths_xy.txt").string(), "20", "100");
  ASSERT_TRUE(posted);
  ASSERT_EQ(posted->status, 200) << posted->body;
  const auto id = json::parse(posted->body)["id"].get<std::string>();
  json run;
  for (int i = 0; i < 600; ++i) {
    run = json::parse(client().Get("/api/runs/" + id)->body);
    if (run["state"] == "done" || run["state"] == "failed") break;
    std::this_thread::sleep_for(100ms);
  }
  ASSERT_EQ(run["state"], "done") << run.dump();
  EXPECT_TRUE(run["summary"]["success"].get<bool>());
  EXPECT_EQ(run["summary"]["robots"], 20);
  EXPECT_GE(run["summary"]["wall_time_s"].get<double>(),
            run["summary"]["makespan_s"].get<double>() / 100);
  // The robot limits given with the upload are the ones the run used.
  const auto robot = slurp(data_ / id / "robot.yaml");
  EXPECT_THAT(robot, HasSubstr("max_speed_mps: 0.75"));
  const auto list = json::parse(client().Get("/api/runs")->body);
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0]["map"], "random-32-32-20.map");
  const auto rec = client().Get("/api/runs/" + id + "/recording");
  ASSERT_EQ(rec->status, 200);
  const auto decoded = serve::decode_recording(rec->body);
  EXPECT_EQ(decoded.robots, 20u);
  EXPECT_GT(decoded.times_s.size(), 10u);
  // Every robot's Type-2 partners add up to the ADG's Type-2 edges, both ways; paths start at
  // the robot's first recorded pose.
  std::size_t waits = 0, waited = 0, actions = 0;
  for (int r = 0; r < 20; ++r) {
    const auto d =
        json::parse(client().Get("/api/runs/" + id + "/robots/" + std::to_string(r))->body);
    for (const auto& p : d["waits_for"]) waits += p["edges"].get<std::size_t>();
    for (const auto& p : d["waited_by"]) waited += p["edges"].get<std::size_t>();
    actions += d["actions"].get<std::size_t>();
    ASSERT_FALSE(d["path"].empty());
    EXPECT_NEAR(d["path"][0][0].get<double>(), decoded.poses[r].x_m, 0.05) << r;
    EXPECT_NEAR(d["path"][0][1].get<double>(), decoded.poses[r].y_m, 0.05) << r;
    EXPECT_GT(d["results"]["finish_time_s"].get<double>(), 0.0);
  }
  EXPECT_EQ(waits, run["summary"]["adg"]["type2"].get<std::size_t>());
  EXPECT_EQ(waited, waits);
  EXPECT_EQ(actions, run["summary"]["total_actions"].get<std::size_t>());
  for (const char* bad : {"/robots/20", "/robots/abc", "/robots/-1", "/robots/99999999"}) {
    EXPECT_EQ(client().Get("/api/runs/" + id + bad)->status, 404) << bad;
  }
}

TEST_F(Serve, ABadUploadGetsTheProblemListAndNothingOutsideDataIsServed) {
  start();
  const auto bad = temp_file("bad_plan.txt");
  std::ofstream(bad) << "Agent 0:(1,1)->(9,9)->\n";  // a jump of 16 cells
  const auto r = upload(bad.string(), "1");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  const auto j = json::parse(r->body);
  ASSERT_FALSE(j["problems"].empty()) << r->body;
  EXPECT_EQ(j["problems"][0]["file"], "paths.txt");
  EXPECT_THAT(j.dump(), HasSubstr(R"("line":1)")) << "the jump is on line 1 of paths.txt";
  EXPECT_EQ(json::parse(client().Get("/api/runs")->body).size(), 0u);
  for (const char* path : {"/api/runs/../../etc/passwd", "/api/runs/%2e%2e%2fserve.out",
                           "/api/runs/run-000001", "/api/runs/upload-1/recording"}) {
    const auto g = client().Get(path);
    ASSERT_TRUE(g);
    EXPECT_EQ(g->status, 404) << path;
  }
  // Limits are checked against the robot model's ranges; a word is not a number.
  httplib::MultipartFormDataItems limits{
      {"map", slurp(b_ / "maps/random-32-32-20.map"), "m.map", ""},
      {"scen", slurp(b_ / "scens/random-32-32-20-random-1.scen"), "s.scen", ""},
      {"plan", slurp(b_ / "smart-examples/example_paths_xy.txt"), "p.txt", ""},
      {"agents", "2", "", ""},
      {"max_speed_mps", "fast", "", ""}};
  auto l = client().Post("/api/runs", limits);
  EXPECT_EQ(l->status, 400);
  EXPECT_THAT(l->body, HasSubstr("max_speed_mps must be a positive number"));
  limits.back() = {"max_turn_rate_radps", "1e9", "", ""};
  l = client().Post("/api/runs", limits);
  EXPECT_EQ(l->status, 400);
  EXPECT_THAT(l->body, HasSubstr("max_turn_rate_radps"));
  for (const char* factor : {"fast", "-1", "1e9", "nan"}) {
    limits.back() = {"real_time_factor", factor, "", ""};
    l = client().Post("/api/runs", limits);
    EXPECT_EQ(l->status, 400) << factor;
    EXPECT_THAT(l->body, HasSubstr("real_time_factor must be a number from 0")) << factor;
  }
  httplib::MultipartFormDataItems missing{{"map", "x", "m.map", ""}};
  const auto m = client().Post("/api/runs", missing);
  EXPECT_EQ(m->status, 400);
  EXPECT_THAT(m->body, HasSubstr("missing the 'scen' file field"));
  std::filesystem::remove(bad);
}

// Regression: uploads were checked with the half-cell ADG footprint whatever their robot, so a
// model too wide for the cells was accepted and only its run failed (and the robot panel's waits
// could differ from the run's). A model half a 1 m cell wide is now refused with the upload.
TEST_F(Serve, AnUploadIsCheckedWithItsRobotsFootprint) {
  const auto config = temp_file("serve_config");
  std::filesystem::create_directories(config / "robots");
  const std::string footbot = slurp(std::string(SMART_SOURCE_DIR) + "/config/robots/footbot.yaml");
  std::ofstream(config / "robots" / "footbot.yaml") << footbot;
  std::string wide = footbot;
  wide.replace(wide.find("radius_m: 0.085"), 15, "radius_m: 0.6");
  std::ofstream(config / "robots" / "wide.yaml") << wide;
  ASSERT_EQ(::setenv("SMART_CONFIG_DIR", config.c_str(), 1), 0);  // smart serve's models
  start();
  ::unsetenv("SMART_CONFIG_DIR");
  httplib::MultipartFormDataItems items{
      {"map", slurp(b_ / "maps/random-32-32-20.map"), "m.map", ""},
      {"scen", slurp(b_ / "scens/random-32-32-20-random-1.scen"), "s.scen", ""},
      {"plan", slurp(b_ / "smart-examples/example_paths_xy.txt"), "p.txt", ""},
      {"agents", "2", "", ""},
      {"robot", "wide", "", ""}};
  const auto r = client().Post("/api/runs", items);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400) << r->body;
  EXPECT_THAT(r->body, HasSubstr("radius 0.6"));
  EXPECT_THAT(r->body, HasSubstr("pick a smaller robot model"));
  EXPECT_EQ(json::parse(client().Get("/api/runs")->body).size(), 0u);
  std::filesystem::remove_all(config);
}

// The live stream of a run: events while it goes, the last one when it ended, with every robot.
// Paced to 50x real time (about 4 s; unpaced about 1 s, which could end before the stream began).
TEST_F(Serve, ALiveStreamFollowsTheRunUntilItEnds) {
  start();
  const auto posted = upload((b_ / "smart-examples/example_paths_xy.txt").string(), "20", "50");
  ASSERT_EQ(posted->status, 200) << posted->body;
  const auto id = json::parse(posted->body)["id"].get<std::string>();
  std::string stream;
  const auto r = client().Get("/api/runs/" + id + "/live", [&](const char* data, size_t n) {
    stream.append(data, n);
    return stream.size() < (64u << 20);
  });
  ASSERT_TRUE(r);
  std::vector<json> events;
  for (std::size_t at = 0; (at = stream.find("data: ", at)) != std::string::npos; at += 6) {
    events.push_back(json::parse(stream.substr(at + 6, stream.find("\n\n", at) - at - 6)));
  }
  ASSERT_GE(events.size(), 2u) << stream.substr(0, 500);
  EXPECT_EQ(events.back()["state"], "done");
  EXPECT_EQ(events.back()["poses"].size(), 20u);
  EXPECT_GT(events.back()["t_s"].get<double>(), 10.0);
  EXPECT_NE(events.front()["state"], "done");
}

// A folder written by `smart run --out` is replayed: listed as done, its summary and recording
// served.
TEST_F(Serve, OpenReplaysASmartRunOutFolder) {
  const auto results = temp_file("serve_open_results");
  const auto r = run_to_folder(results, "20", kServeOpen, "serve_open_run");
  ASSERT_EQ(r.code, 0) << r.out;
  start({"--open", results.string()});
  const auto run = json::parse(client().Get("/api/runs/run-000001")->body);
  EXPECT_EQ(run["state"], "done");
  EXPECT_EQ(run["summary"]["aet_s"], r.last_json()["aet_s"]);
  EXPECT_EQ(serve::decode_recording(client().Get("/api/runs/run-000001/recording")->body).robots,
            20u);
  // Finished actions over time: rising to every action, at the makespan.
  const auto curve = json::parse(client().Get("/api/runs/run-000001/progress")->body);
  EXPECT_EQ(curve["finished"].back(), run["summary"]["total_actions"]);
  EXPECT_DOUBLE_EQ(curve["t_s"].back().get<double>(), run["summary"]["makespan_s"].get<double>());
  // Every results file downloads as written; nothing else does.
  EXPECT_THAT(run["files"].dump(), HasSubstr("actions.csv"));
  for (const char* f : {"summary.json", "robots.csv", "actions.csv", "states.csv"}) {
    const auto got = client().Get(std::string("/api/runs/run-000001/results/") + f);
    ASSERT_EQ(got->status, 200) << f;
    EXPECT_EQ(got->body, slurp(results / f)) << f;
    EXPECT_THAT(got->get_header_value("Content-Disposition"), HasSubstr("run-000001-"));
  }
  for (const char* bad : {"robot.yaml", "..%2fmap.map", "recording-v2.smrc", "run.out"}) {
    EXPECT_EQ(client().Get(std::string("/api/runs/run-000001/results/") + bad)->status, 404) << bad;
  }
  std::filesystem::remove_all(results);
}

// Issue 26: `make demo`'s serve command failed on its second use, a restarted server listed none
// of the old runs and aborted on its first upload, and a second server on a port in use started
// anyway and shared one data folder. Now: refused naming the port or the folder; a restart
// serves the old runs and continues their ids.
TEST_F(Serve, ARestartedServerServesItsRunsAndASecondServerIsRefused) {
  const auto results = temp_file("serve_restart_results");
  const auto r = run_to_folder(results, "20", kServeRestart, "serve_restart_run");
  ASSERT_EQ(r.code, 0) << r.out;
  start({"--open", results.string()});
  const auto other = temp_file("serve_restart_other");
  const auto same_port =
      run_smart({"serve", "--port", std::to_string(port_), "--data", other.string()}, 60s,
                "serve_port", true);
  EXPECT_EQ(same_port.code, 3) << same_port.out;
  EXPECT_THAT(same_port.out, HasSubstr("the port is in use"));
  const auto same_data =
      run_smart({"serve", "--port", "0", "--data", data_.string()}, 60s, "serve_data", true);
  EXPECT_EQ(same_data.code, 3) << same_data.out;
  EXPECT_THAT(same_data.out, HasSubstr("is in use by another `smart serve`"));
  server_.reset();  // stopped
  port_ = 0;
  start({"--open", results.string()});  // the same command again, as `make demo` prints it
  const auto list = json::parse(client().Get("/api/runs")->body);
  ASSERT_EQ(list.size(), 2u) << list.dump();
  EXPECT_EQ(list[0]["id"], "run-000001");
  EXPECT_EQ(list[0]["state"], "done");
  EXPECT_EQ(list[1]["id"], "run-000002");
  EXPECT_EQ(serve::decode_recording(client().Get("/api/runs/run-000001/recording")->body).robots,
            20u);
  std::filesystem::remove_all(results);
  std::filesystem::remove_all(other);
}

// POST /api/results: a results folder (and the run's map) uploaded over HTTP is replayed; what
// is not a results file is ignored; bad files are refused naming the file and line.
TEST_F(Serve, AnUploadedResultsFolderIsReplayedAndBadOnesAreRefused) {
  const auto results = temp_file("serve_upload_results");
  const auto r = run_to_folder(results, "5", kServeUpload, "serve_upload_results_run");
  ASSERT_EQ(r.code, 0) << r.out;
  start();
  auto items = [&](const std::string& states) {
    httplib::MultipartFormDataItems f{
        {"files", slurp(results / "summary.json"), "out/summary.json", ""},
        {"files", states, "out/states.csv", ""},
        {"files", "evil", "../../evil.csv", ""},
        {"map", slurp(b_ / "maps/random-32-32-20.map"), "random-32-32-20.map", ""}};
    return f;
  };
  auto bad = items(slurp(results / "states.csv") + "1.5,zero,1,1,0\n");
  auto got = client().Post("/api/results", bad);
  ASSERT_EQ(got->status, 400);
  EXPECT_THAT(got->body, HasSubstr("states.csv line"));
  // A forged robot id would make the recording (every robot in every frame) huge.
  auto forged = items(slurp(results / "states.csv") + "1.5,9999999,1,1,0,0,0,0,0,0\n");
  got = client().Post("/api/results", forged);
  ASSERT_EQ(got->status, 400);
  EXPECT_THAT(got->body, HasSubstr("names robot 9999999 but summary.json has 5 robots"));
  // A malformed robots.csv is refused naming its line (the robot panel answered 404 later).
  auto robots = items(slurp(results / "states.csv"));
  robots.insert(robots.begin(),
                {"files", slurp(results / "robots.csv") + "7,soon,0,0,1,\n", "out/robots.csv", ""});
  got = client().Post("/api/results", robots);
  ASSERT_EQ(got->status, 400);
  EXPECT_THAT(got->body, HasSubstr("robots.csv line 7"));
  bad.pop_back();  // no map
  got = client().Post("/api/results", bad);
  EXPECT_THAT(got->body, HasSubstr("no map"));
  got = client().Post("/api/results", items(slurp(results / "states.csv")));
  ASSERT_EQ(got->status, 200) << got->body;
  const auto id = json::parse(got->body)["id"].get<std::string>();
  const auto run = json::parse(client().Get("/api/runs/" + id)->body);
  EXPECT_EQ(run["state"], "done");
  EXPECT_EQ(run["files"], json::parse(R"(["summary.json", "states.csv"])"));
  EXPECT_EQ(serve::decode_recording(client().Get("/api/runs/" + id + "/recording")->body).robots,
            5u);
  EXPECT_FALSE(std::filesystem::exists(data_ / "evil.csv"));
  EXPECT_FALSE(std::filesystem::exists(data_.parent_path() / "evil.csv"));
  std::filesystem::remove_all(results);
}

// --watch: a mixed run (two simulated robots and an emulated JetBot's agent) seen live from the
// domain by a read-only server, which does not disturb it: the run succeeds.
TEST_F(Serve, WatchShowsAMixedRunOnTheDomainLive) {
  MixedFleet fleet("serve_watch");
  start(
      {"--watch", "--map", fleet.map, "--cell-m", "0.4", "--domain", std::to_string(kServeWatch)});
  auto sim = fleet.start_sim(kServeWatch);
  auto agent = MixedFleet::start_agent_at_start(kServeWatch, "/dev/null");
  const auto monitor_out = temp_file("serve_watch_monitor.out");
  auto monitor = start_smart(fleet.monitor_args(kServeWatch), monitor_out);
  std::set<std::string> statuses;
  std::optional<double> jetbot_first_x;
  double jetbot_moved_m = 0;
  json last;
  for (int i = 0; i < 600 && !monitor.wait(0ms).has_value(); ++i) {
    last = json::parse(client().Get("/api/watch")->body);
    for (const auto& r : last["robots"]) {
      statuses.insert(r["status"].get<std::string>());
      if (r["id"] != 2) continue;
      const double y = r["y_m"].get<double>();
      if (!jetbot_first_x) jetbot_first_x = y;
      jetbot_moved_m = std::max(jetbot_moved_m, std::abs(y - *jetbot_first_x));
    }
    std::this_thread::sleep_for(100ms);
  }
  ASSERT_EQ(monitor.wait(60s).value_or(-1), 0) << slurp(monitor_out);
  EXPECT_TRUE(summary_in(slurp(monitor_out))["success"].get<bool>());
  EXPECT_EQ(last["robots"].size(), 3u) << last.dump();
  EXPECT_EQ(last["monitor"]["pid"], monitor.pid()) << last.dump();
  EXPECT_DOUBLE_EQ(last["cell_m"].get<double>(), 0.4);
  EXPECT_TRUE(statuses.count("moving")) << "no robot was ever seen moving";
  // The JetBot drives 4 cells (1.6 m) down the map: the watch saw most of it.
  EXPECT_GT(jetbot_moved_m, 1.0);
  EXPECT_EQ(last["rejected_samples"], 0);
  EXPECT_EQ(client().Get("/api/watch/map")->body, slurp(fleet.map));
  (void)agent.wait(10s);
  (void)sim.wait(10s);
  std::filesystem::remove(monitor_out);
}

// Issue 25, a server an attacker can't take down: a summary.json nested 100 000 deep crashed it
// on the next GET; a 16 KB results upload became a 668 MB recording; a refused upload left its
// staging folder.
TEST_F(Serve, AResultsUploadNestedDeepOrMakingAHugeRecordingIsRefusedAndLeavesNothing) {
  start();
  const auto post = [&](const std::string& summary, const std::string& states) {
    httplib::MultipartFormDataItems items{
        {"files", summary, "summary.json", ""},
        {"files", states, "states.csv", ""},
        {"map", slurp(b_ / "maps/random-32-32-20.map"), "random-32-32-20.map", ""}};
    return client().Post("/api/results", items);
  };
  const auto nested = post(std::string(100000, '[') + std::string(100000, ']'),
                           "t_s,robot,x_m,y_m,yaw_rad\n0,0,1,1,0\n");
  ASSERT_TRUE(nested);
  EXPECT_EQ(nested->status, 400);
  EXPECT_THAT(nested->body, HasSubstr("summary.json nests deeper than 32 levels"));
  std::string states = "t_s,robot,x_m,y_m,yaw_rad\n";
  for (int t = 0; t < 500; ++t) states += std::to_string(t) + ",99999,1,1,0\n";
  const auto huge = post(R"({"robots": 100000})", states);
  ASSERT_TRUE(huge);
  EXPECT_EQ(huge->status, 400);
  EXPECT_THAT(huge->body, HasSubstr("would make a recording of 333 MB"));
  const auto list = client().Get("/api/runs");
  ASSERT_TRUE(list) << "the server went down";
  EXPECT_EQ(json::parse(list->body).size(), 0u);
  for (const auto& e : std::filesystem::directory_iterator(data_)) {
    EXPECT_EQ(e.path().filename().string().rfind("upload-", 0), std::string::npos)
        << "a refused upload left " << e.path();
  }
}

// Eight concurrent 60 MB uploads took 1.4 GB: cpp-httplib held each body and then its parsed
// fields. Uploads are now read field by field within one memory budget for all of them; past it
// the server answers 503 (retry later), keeps nothing and stays up.
TEST_F(Serve, UploadsPastTheMemoryBudgetGet503AndLeaveNothing) {
  start({"--max-upload-memory-mb", "1"});
  std::string states = "t_s,robot,x_m,y_m,yaw_rad\n";
  while (states.size() < (3u << 19)) states += "0.5,0,1.25,1.25,0\n";  // 1.5 MB
  httplib::MultipartFormDataItems big{{"files", R"({"robots": 1})", "summary.json", ""},
                                      {"files", states, "states.csv", ""},
                                      {"map", "type octile", "m.map", ""}};
  const auto refused = client().Post("/api/results", big);
  ASSERT_TRUE(refused) << "the server went down";
  EXPECT_EQ(refused->status, 503);
  EXPECT_THAT(refused->body, HasSubstr("reading other uploads (1 MB at once)"));
  const auto small = client().Post("/api/results", {{"files", "{}", "summary.json", ""}});
  ASSERT_TRUE(small);
  EXPECT_EQ(small->status, 400);  // within the budget: read, and refused for what it is
  for (const auto& e : std::filesystem::directory_iterator(data_)) {
    EXPECT_EQ(e.path().filename().string().rfind("upload-", 0), std::string::npos)
        << "a refused upload left " << e.path();
  }
}

// A 500 put the exception's text in a header; now it says where to look, and the log says more.
TEST_F(Serve, AnInternalErrorAnswersWithoutItsExceptionText) {
  const auto results = temp_file("serve_error_results");
  const auto r = run_to_folder(results, "20", kServeHardening, "serve_error_run");
  ASSERT_EQ(r.code, 0) << r.out;
  start({"--open", results.string()});
  // Its recording is gone and its states.csv damaged behind the server's back.
  std::filesystem::remove(data_ / "run-000001" / "recording-v2.smrc");
  std::ofstream(data_ / "run-000001" / "results" / "states.csv") << "t_s,robot\n0,zero\n";
  const auto got = client().Get("/api/runs/run-000001/recording");
  ASSERT_TRUE(got);
  EXPECT_EQ(got->status, 500);
  EXPECT_EQ(json::parse(got->body)["error"], "internal error; the server's log says more");
  EXPECT_FALSE(got->has_header("EXCEPTION_WHAT"));
  EXPECT_THAT(got->body, ::testing::Not(HasSubstr("states.csv")));
  std::filesystem::remove_all(results);
}

TEST_F(Serve, WithATokenUploadsNeedItAndEveryAnswerCarriesTheContentPolicy) {
  start({"--token", "s3cret"});
  httplib::MultipartFormDataItems items{{"files", "{}", "summary.json", ""}};
  const auto without = client().Post("/api/results", items);
  ASSERT_TRUE(without);
  EXPECT_EQ(without->status, 401);
  EXPECT_THAT(without->body, HasSubstr("Authorization: Bearer TOKEN"));
  const auto with = client().Post("/api/results", {{"Authorization", "Bearer s3cret"}}, items);
  ASSERT_TRUE(with);
  EXPECT_EQ(with->status, 400);  // past the token: the upload's own problem
  const auto list = client().Get("/api/runs");
  EXPECT_THAT(list->get_header_value("Content-Security-Policy"), HasSubstr("script-src 'self'"));
  EXPECT_EQ(list->get_header_value("X-Content-Type-Options"), "nosniff");
}

// Eight slow connections or eight open live streams froze the API (a thread each, 8 threads).
TEST_F(Serve, SlowClientsAndOpenLiveStreamsLeaveTheApiAnswering) {
  start();
  std::atomic<bool> done{false};
  std::atomic<int> open{0};
  std::vector<std::jthread> clients;  // joined last, after `stop` below has ended them
  struct Stop {
    std::atomic<bool>& done;
    ~Stop() { done = true; }  // on every way out, a failed ASSERT too (it crashed the test)
  } stop{done};
  for (int i = 0; i < 12; ++i) {  // a request one byte at a time, never finished
    clients.emplace_back([&] {
      const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
      sockaddr_in a{};
      a.sin_family = AF_INET;
      a.sin_port = htons(static_cast<uint16_t>(port_));
      a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
      if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) == 0) {
        const std::string req = "GET /api/runs HTTP/1.1\r\nHost: x\r\nX-Slow: ";
        for (std::size_t k = 0; !done; ++k) {
          const char c = k < req.size() ? req[k] : 'a';
          if (::send(fd, &c, 1, MSG_NOSIGNAL) != 1) break;
          std::this_thread::sleep_for(200ms);
        }
      }
      ::close(fd);
    });
  }
  const auto up = upload((b_ / "smart-examples/example_paths_xy.txt").string(), "20", "1");
  ASSERT_TRUE(up) << "the upload got no answer: " << httplib::to_string(up.error());
  const auto id = json::parse(up->body)["id"].get<std::string>();
  for (int i = 0; i < 16; ++i) {
    clients.emplace_back([&, id] {
      bool first = true;
      client().Get("/api/runs/" + id + "/live", [&](const char*, size_t) {
        if (first) ++open;
        first = false;
        return !done.load();
      });
    });
  }
  const auto deadline = std::chrono::steady_clock::now() + 60s;
  while (open < 16 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(10ms);
  EXPECT_EQ(open.load(), 16) << "live streams that never started";
  const auto extra = client().Get("/api/runs/" + id + "/live");
  ASSERT_TRUE(extra) << "the API froze";
  EXPECT_EQ(extra->status, 503);
  EXPECT_THAT(extra->body, HasSubstr("16 live streams are open"));
  const auto list = client().Get("/api/runs");
  ASSERT_TRUE(list) << "the API froze";
  EXPECT_EQ(list->status, 200);
}

TEST_F(Serve, WithoutWatchTheWatchApiSaysHowToTurnItOn) {
  start();
  const auto r = client().Get("/api/watch");
  EXPECT_EQ(r->status, 404);
  EXPECT_THAT(r->body, HasSubstr("smart serve --watch"));
}

}  // namespace
}  // namespace smart::test
