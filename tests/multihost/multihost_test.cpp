// Runs across hosts: the monitor, sim hosts and emulated-JetBot agents in network namespaces of
// their own (support/netns_lab.hpp), talking DDS over veth links and a bridge with
// `--network network` (multicast discovery, as on a LAN). ctest label `multihost`; each test
// builds its own lab and removes it, and skips only where namespaces cannot be created.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <thread>

#include "support/mixed_fleet.hpp"
#include "support/monitor_fixtures.hpp"
#include "support/netns_lab.hpp"
#include "support/smart_process.hpp"
#include "support/states_compare.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;

class Multihost : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why;
    lab_ = NetnsLab::create(3, why);
    if (!lab_) GTEST_SKIP() << why;
  }
  // `args` on the network, in a run (partition) of this test's own.
  static std::vector<std::string> on_lan(std::vector<std::string> args, const std::string& run) {
    args.insert(args.end(), {"--network", "network", "--run", run});
    return args;
  }
  // Waits for `p` and returns its report (the last JSON object it printed).
  static nlohmann::json report_of(common::ChildProcess& p, const std::filesystem::path& out,
                                  std::chrono::seconds timeout) {
    const auto code = p.wait(timeout);
    if (!code) p.terminate();
    EXPECT_EQ(code.value_or(-1), 0) << slurp(out);
    return last_json_line(slurp(out));
  }
  std::unique_ptr<NetnsLab> lab_;
};

// 20 robots of SMART's example plan on random-32-32-20 (benchmark data).
class MultihostBenchmark : public Multihost {
 protected:
  void SetUp() override {
    b_ = benchmarks_dir();
    ASSERT_TRUE(std::filesystem::exists(b_)) << smart::test::no_benchmarks(b_);
    Multihost::SetUp();
  }
  std::vector<std::string> world(const std::string& command, int domain) const {
    return {command,
            "--map",
            (b_ / "maps/random-32-32-20.map").string(),
            "--scen",
            (b_ / "scens/random-32-32-20-random-1.scen").string(),
            "--agents",
            "20",
            "--domain",
            std::to_string(domain)};
  }
  std::vector<std::string> monitor(int domain, const std::filesystem::path& out) const {
    auto a = world("monitor", domain);
    a.insert(a.end(), {"--plan", (b_ / "smart-examples/example_paths_xy.txt").string(), "--axis",
                       "xy", "--no-progress", "--out", out.string()});
    return a;
  }
  // The same plan on this host alone (`smart run`, loopback): the reference.
  nlohmann::json one_host_run(const std::filesystem::path& out,
                              int domain = kMultihostLockstep + 1) const {
    auto a = monitor(domain, out);
    a[0] = "run";
    const auto r = run_smart(a, 120s, "one_host");
    EXPECT_EQ(r.code, 0) << r.out;
    return r.last_json();
  }
  // Monitor on host 0 and sim on host 1; their summaries.
  nlohmann::json two_host_run(int domain, const std::filesystem::path& out,
                              const std::vector<std::string>& extra = {}) const {
    const std::string run = "lan" + std::to_string(domain);
    auto sim_args = on_lan(world("sim", domain), run);
    auto mon_args = on_lan(monitor(domain, out), run);
    sim_args.insert(sim_args.end(), extra.begin(), extra.end());
    mon_args.insert(mon_args.end(), extra.begin(), extra.end());
    const auto sim_out = temp_file("lan_sim" + std::to_string(domain));
    auto sim = lab_->start_smart(1, sim_args, sim_out);
    const auto mon_out = temp_file("lan_monitor" + std::to_string(domain));
    auto mon = lab_->start_smart(0, mon_args, mon_out);
    auto summary = report_of(mon, mon_out, 120s);
    const auto sim_report = report_of(sim, sim_out, 15s);
    EXPECT_TRUE(sim_report["stopped_by_monitor"].get<bool>()) << sim_report.dump();
    std::filesystem::remove(sim_out);
    std::filesystem::remove(mon_out);
    return summary;
  }
  static void expect_same_run(const nlohmann::json& a, const std::filesystem::path& a_dir,
                              const nlohmann::json& b, const std::filesystem::path& b_dir) {
    ASSERT_TRUE(a["success"].get<bool>()) << a.dump();
    ASSERT_TRUE(b["success"].get<bool>()) << b.dump();
    for (const char* key :
         {"aet_s", "makespan_s", "sim_time_s", "finished_actions", "collisions"}) {
      EXPECT_EQ(a[key], b[key]) << key;
    }
    EXPECT_EQ(slurp(a_dir / "robots.csv"), slurp(b_dir / "robots.csv"));  // every finish time
  }
  std::filesystem::path b_;
};

TEST_F(MultihostBenchmark, LockstepRunWithMonitorAndSimOnTwoHostsGivesTheOneHostSummary) {
  const auto one_dir = temp_file("one_host"), lan_dir = temp_file("lan_host");
  const auto one = one_host_run(one_dir);
  const uint64_t before = lab_->sent_packets(1);
  const auto lan = two_host_run(kMultihostLockstep, lan_dir);
  expect_same_run(one, one_dir, lan, lan_dir);
  EXPECT_GT(lab_->sent_packets(1) - before, 100u) << "the run crossed the sim host's link";
  std::filesystem::remove_all(one_dir);
  std::filesystem::remove_all(lan_dir);
}

// The sim as two shards (`smart sim --shard I/2`), each on a host of its own, the monitor on a
// third: robots are handed between the hosts and the results are the one-host run's.
TEST_F(MultihostBenchmark, ShardedSimOnTwoHostsGivesTheOneHostResults) {
  const auto one_dir = temp_file("one_host_sharded"), lan_dir = temp_file("lan_sharded");
  const auto one = one_host_run(one_dir, kMultihostSharded + 1);
  const std::string run = "shards";
  std::vector<common::ChildProcess> shards;
  std::vector<std::filesystem::path> outs;
  for (int s = 0; s < 2; ++s) {
    auto a = on_lan(world("sim", kMultihostSharded), run);
    a.insert(a.end(), {"--shard", std::to_string(s) + "/2"});
    outs.push_back(temp_file("lan_shard" + std::to_string(s)));
    shards.push_back(lab_->start_smart(1 + s, a, outs.back()));
  }
  const auto mon_out = temp_file("lan_shard_monitor");
  auto mon = lab_->start_smart(0, on_lan(monitor(kMultihostSharded, lan_dir), run), mon_out);
  const auto lan = report_of(mon, mon_out, 120s);
  uint64_t adopted = 0;
  for (int s = 0; s < 2; ++s) {
    const auto r = report_of(shards[s], outs[s], 15s);
    EXPECT_TRUE(r["stopped_by_monitor"].get<bool>()) << r.dump();
    adopted += r["handovers_in"].get<uint64_t>();
    std::filesystem::remove(outs[s]);
  }
  EXPECT_GT(adopted, 0u) << "no robot crossed between the shards' hosts";
  expect_same_run(one, one_dir, lan, lan_dir);
  std::filesystem::remove(mon_out);
  std::filesystem::remove_all(one_dir);
  std::filesystem::remove_all(lan_dir);
}

TEST_F(MultihostBenchmark, SecureRunAcrossHostsGivesTheSameSummary) {
  const auto keys = temp_file("lan_keystore");
  std::filesystem::remove_all(keys);
  const auto init = run_smart({"security", "init", "--out", keys.string(), "--days", "2"}, 60s,
                              "lan_security_init");
  ASSERT_EQ(init.code, 0) << init.out;
  const auto one_dir = temp_file("one_host_s"), lan_dir = temp_file("lan_host_s");
  const auto one = one_host_run(one_dir);
  const auto lan = two_host_run(kMultihostSecure, lan_dir, {"--security", keys.string()});
  expect_same_run(one, one_dir, lan, lan_dir);
  std::filesystem::remove_all(keys);
  std::filesystem::remove_all(one_dir);
  std::filesystem::remove_all(lan_dir);
}

// A lifelong run across hosts: `smart monitor --lifelong` on host 0 and `smart sim --lifelong` on
// host 1, each loading the same seeded problem, in lock-step over the LAN: the events, tasks and
// states of the one-host `smart run --lifelong`.
TEST_F(MultihostBenchmark, LifelongRunWithMonitorAndSimOnTwoHostsIsTheOneHostRun) {
  const std::vector<std::string> problem{
      "--tasks",        "random", "--map",    (b_ / "maps/random-32-32-20.map").string(),
      "--agents",       "20",     "--seed",   "9",
      "--task-errands", "1",      "--domain", std::to_string(kMultihostLifelong)};
  const auto lan_dir = temp_file("lan_lifelong"), one_dir = temp_file("one_lifelong");
  for (const auto& d : {lan_dir, one_dir}) std::filesystem::remove_all(d);
  const std::string run = "lifelong";
  auto sim_args = problem;
  sim_args.insert(sim_args.begin(), "sim");
  auto mon_args = problem;
  mon_args.insert(mon_args.begin(), "monitor");
  mon_args.insert(mon_args.end(), {"--duration-s", "40", "--no-progress", "--out", lan_dir});
  const auto sim_out = temp_file("lan_lifelong_sim"), mon_out = temp_file("lan_lifelong_mon");
  const uint64_t before = lab_->sent_packets(1);
  auto sim = lab_->start_smart(1, on_lan(sim_args, run), sim_out);
  auto mon = lab_->start_smart(0, on_lan(mon_args, run), mon_out);
  const auto lan = report_of(mon, mon_out, 120s);
  EXPECT_TRUE(report_of(sim, sim_out, 15s)["stopped_by_monitor"].get<bool>());
  EXPECT_GT(lab_->sent_packets(1) - before, 100u) << "the run crossed the sim host's link";
  ASSERT_TRUE(lan["success"].get<bool>()) << lan.dump();
  EXPECT_GT(lan["lifelong"]["tasks_finished"].get<int>(), 0);
  // The reference: the same problem on this host alone (the two-host run is over).
  auto one_args = problem;
  one_args.insert(one_args.begin(), "run");
  one_args.insert(one_args.end(), {"--duration-s", "40", "--no-progress", "--out", one_dir});
  ASSERT_EQ(run_smart(one_args, 120s, "one_lifelong").code, 0);
  for (const char* name : {"events.csv", "tasks.csv"}) {
    EXPECT_EQ(slurp(lan_dir / name), slurp(one_dir / name)) << name << " differs across hosts";
  }
  EXPECT_EQ(compare_state_rows(slurp(lan_dir / "states.csv"), slurp(one_dir / "states.csv")), "")
      << "states.csv differs across hosts";
  for (const auto& f : {sim_out, mon_out, lan_dir, one_dir}) std::filesystem::remove_all(f);
}

// The mixed run of support/mixed_fleet.hpp with every process on a host of its own: monitor on
// host 0, the sim host (robots 0 and 1) on host 1, robot 2's emulated JetBot agent on host 2.
class MultihostMixed : public Multihost {
 protected:
  void SetUp() override {
    Multihost::SetUp();
    if (lab_) fleet_.emplace("lan_mixed");
  }
  struct Processes {
    common::ChildProcess sim, agent, monitor;
  };
  Processes start(int domain) const {
    const std::string run = "mixed" + std::to_string(domain);
    auto mon = on_lan(fleet_->monitor_args(domain), run);
    mon.insert(mon.end(), {"--out", temp_file("lan_mixed_out").string()});
    return {lab_->start_smart(1, on_lan(fleet_->sim_args(domain), run), "/dev/null"),
            lab_->start_smart(2, on_lan(MixedFleet::agent_at_start_args(domain), run), agent_out_),
            lab_->start_smart(0, mon, monitor_out_)};
  }
  // Every action finished once: success (robots verified on their goals, so none repeated a
  // move), all actions counted, robot 2's agent at its last action and stopped by the monitor.
  void expect_complete(Processes& p) const {
    const auto summary = report_of(p.monitor, monitor_out_, 90s);
    EXPECT_TRUE(summary["success"].get<bool>()) << summary.dump();
    EXPECT_EQ(summary["finished_actions"], summary["total_actions"]);
    EXPECT_EQ(summary["rejected_progress"], 0);
    const auto agent = report_of(p.agent, agent_out_, 15s);
    EXPECT_EQ(agent["finished_seq"].get<int>() + 1, 9) << agent.dump();
    EXPECT_TRUE(agent["stopped_by_monitor"].get<bool>());
    EXPECT_EQ(p.sim.wait(15s).value_or(-1), 0);
  }
  void TearDown() override {
    std::filesystem::remove(agent_out_);
    std::filesystem::remove(monitor_out_);
    std::filesystem::remove_all(temp_file("lan_mixed_out"));
  }
  std::optional<MixedFleet> fleet_;
  std::filesystem::path agent_out_ = temp_file("lan_agent.out");
  std::filesystem::path monitor_out_ = temp_file("lan_monitor.out");
};

TEST_F(MultihostMixed, AgentSimAndMonitorEachOnTheirOwnHostCompleteThePlan) {
  auto p = start(kMultihostMixed);
  expect_complete(p);
}

// 20 % of the agent host's packets lost each way (nftables): DDS repairs it.
TEST_F(MultihostMixed, APacketLossyAgentLinkStillFinishesEveryActionExactlyOnce) {
  ASSERT_TRUE(lab_->set_loss(2, 200));
  auto p = start(kMultihostLoss);
  expect_complete(p);
  EXPECT_GT(lab_->dropped_packets(2), 10u) << "the loss rules dropped packets";
}

// The agent host's link is cut for 3 s once its robot is moving, then restored: the run
// resumes and completes (the monitor waits up to its --timeout-s, 15 s, for a silent host).
TEST_F(MultihostMixed, AnAgentLinkCutAndRestoredMidRunResumes) {
  auto p = start(kMultihostCut);
  std::this_thread::sleep_for(4s);
  ASSERT_TRUE(p.monitor.running()) << slurp(monitor_out_);
  ASSERT_TRUE(lab_->cut(2));
  const uint64_t sent = lab_->sent_packets(2);
  std::this_thread::sleep_for(3s);
  // Only what nftables' inet family does not see (ARP) leaves while the link is cut; DDS sends
  // tens of packets a second.
  EXPECT_LT(lab_->sent_packets(2) - sent, 10u) << "the link was cut";
  EXPECT_GT(lab_->dropped_packets(2), 10u);
  ASSERT_TRUE(p.monitor.running()) << "the monitor waits for the silent host";
  ASSERT_TRUE(lab_->restore(2));
  expect_complete(p);
}

}  // namespace
}  // namespace smart::test
