// A sharded sim (`smart run --sim-hosts N`, `smart sim --shard I/N`; sim/shard.hpp) gives the
// unsharded run's results exactly: for benchmark plans executed without contacts every robot's
// finish time, every action's finish time, AET and makespan are identical with 1, 2 and 4
// shards, while robots cross between the shards' strips.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/monitor_fixtures.hpp"
#include "support/smart_process.hpp"

namespace smart::test {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

struct Plan {
  std::string map, scen, plan, axis, agents;
};

class Sharded : public ::testing::Test {
 protected:
  void SetUp() override {
    b_ = benchmarks_dir();
    ASSERT_TRUE(std::filesystem::exists(b_)) << smart::test::no_benchmarks(b_);
  }
  Plan plan(const std::string& map, const std::string& scen, const std::string& plan,
            const std::string& axis, const std::string& agents) const {
    return {(b_ / "maps" / map).string(), (b_ / "scens" / scen).string(),
            (b_ / "smart-examples" / plan).string(), axis, agents};
  }
  std::vector<std::string> run_args(const Plan& p, int domain) const {
    return {"run",
            "--map",
            p.map,
            "--scen",
            p.scen,
            "--plan",
            p.plan,
            "--axis",
            p.axis,
            "--agents",
            p.agents,
            "--domain",
            std::to_string(domain),
            "--no-progress"};
  }
  // Runs the plan with each shard count; every result folder's robots.csv and actions.csv must
  // equal the unsharded run's byte for byte.
  void expect_identical(const Plan& p, int domain, const std::string& tag) {
    std::string robots, actions;
    nlohmann::json first;
    for (const int hosts : {1, 2, 4}) {
      SCOPED_TRACE(std::to_string(hosts) + " sim hosts");
      const auto out = temp_file(tag + "_" + std::to_string(hosts));
      std::filesystem::remove_all(out);
      auto args = run_args(p, domain);
      args.insert(args.end(), {"--sim-hosts", std::to_string(hosts), "--out", out.string()});
      const auto r = run_smart(args, 120s, tag, true);
      ASSERT_EQ(r.code, 0) << r.out;
      const auto j = last_json_line(r.out);
      EXPECT_TRUE(j["success"].get<bool>());
      EXPECT_EQ(j["collisions"], 0);
      EXPECT_EQ(j["sim_hosts"], hosts);
      if (hosts > 1) {
        EXPECT_GT(j["sim_handovers"].get<int>(), 0) << "no robot crossed a strip";
      }
      if (hosts == 1) {
        first = j;
        robots = slurp(out / "robots.csv");
        actions = slurp(out / "actions.csv");
      } else {
        EXPECT_EQ(j["aet_s"], first["aet_s"]);
        EXPECT_EQ(j["makespan_s"], first["makespan_s"]);
        EXPECT_EQ(slurp(out / "robots.csv"), robots);
        EXPECT_EQ(slurp(out / "actions.csv"), actions);
      }
      std::filesystem::remove_all(out);
    }
  }
  std::filesystem::path b_;
};

TEST_F(Sharded, SmartsFiftyRobotExampleIsIdenticalOnOneTwoAndFourShards) {
  expect_identical(plan("random-32-32-20.map", "random-32-32-20-random-1.scen",
                        "example_paths_xy.txt", "xy", "50"),
                   kShardedSmall, "sharded_small");
}

TEST_F(Sharded, SmartsWarehousePlanIsIdenticalOnOneTwoAndFourShards) {
  expect_identical(plan("warehouse-10-20-10-2-1.map", "warehouse-10-20-10-2-1-random-1.scen",
                        "scen_1_paths.txt", "rowcol", "40"),
                   kShardedWarehouse, "sharded_warehouse");
}

TEST_F(Sharded, SmartsThousandRobotWarehousePlanIsIdenticalOnOneTwoAndFourShards) {
  expect_identical(plan("warehouse-10-20-10-2-1.map", "warehouse-10-20-10-2-1-random-1.scen",
                        "scen_1_1000_paths.txt", "rowcol", "40"),
                   kShardedWarehouse1000, "sharded_warehouse_1000");
}

// The shards as separate `smart sim --shard I/2` processes started by hand next to a
// `smart monitor`: each reports the robots it adopted from the other, and the run's results are
// the unsharded run's.
TEST_F(Sharded, ShardProcessesStartedByHandHandRobotsOverAndMatchTheUnshardedRun) {
  const Plan p = plan("random-32-32-20.map", "random-32-32-20-random-1.scen",
                      "example_paths_xy.txt", "xy", "50");
  const auto ref = temp_file("sharded_ref"), out = temp_file("sharded_hand");
  std::filesystem::remove_all(ref);
  std::filesystem::remove_all(out);
  auto ref_args = run_args(p, kShardedProcesses);
  ref_args.insert(ref_args.end(), {"--out", ref.string()});
  ASSERT_EQ(run_smart(ref_args, 60s, "sharded_ref").code, 0);
  const std::vector<std::string> world{
      "--map",    p.map,    "--scen",   p.scen,
      "--agents", "50",     "--domain", std::to_string(kShardedProcesses),
      "--run",    "by-hand"};
  std::vector<common::ChildProcess> shards;
  for (const char* s : {"0/2", "1/2"}) {
    auto args = world;
    args.insert(args.begin(), "sim");
    args.insert(args.end(), {"--shard", s});
    shards.push_back(start_smart(args, temp_file(std::string("shard_") + s[0] + ".json")));
  }
  auto mon = world;
  mon.insert(mon.begin(), "monitor");
  mon.insert(mon.end(), {"--plan", p.plan, "--axis", "xy", "--out", out.string(), "--no-progress"});
  const auto r = run_smart(mon, 60s, "sharded_monitor");
  ASSERT_EQ(r.code, 0) << r.out;
  uint64_t adopted = 0;
  for (int s = 0; s < 2; ++s) {
    ASSERT_EQ(shards[s].wait(10s), 0);
    const auto j = last_json_line(slurp(temp_file("shard_" + std::to_string(s) + ".json")));
    EXPECT_TRUE(j["ok"].get<bool>()) << j.dump();
    EXPECT_TRUE(j["stopped_by_monitor"].get<bool>());
    adopted += j["handovers_in"].get<uint64_t>();
  }
  EXPECT_GT(adopted, 0u);
  EXPECT_EQ(slurp(out / "robots.csv"), slurp(ref / "robots.csv"));
  EXPECT_EQ(slurp(out / "actions.csv"), slurp(ref / "actions.csv"));
  std::filesystem::remove_all(ref);
  std::filesystem::remove_all(out);
}

// Under DDS Security the shards' exchange is a topic of the `sim` identity's permissions.
TEST_F(Sharded, ASecureShardedRunMatchesTheUnshardedRun) {
  const auto keys = temp_file("sharded_keys"), ref = temp_file("secure_ref"),
             out = temp_file("secure_sharded");
  for (const auto& d : {keys, ref, out}) std::filesystem::remove_all(d);
  ASSERT_EQ(run_smart({"security", "init", "--out", keys.string()}, 60s, "sharded_keys").code, 0);
  const Plan p = plan("random-32-32-20.map", "random-32-32-20-random-1.scen",
                      "example_paths_xy.txt", "xy", "30");
  auto plain = run_args(p, kShardedSecure);
  plain.insert(plain.end(), {"--out", ref.string()});
  ASSERT_EQ(run_smart(plain, 60s, "secure_ref").code, 0);
  auto secure = run_args(p, kShardedSecure);
  secure.insert(secure.end(),
                {"--sim-hosts", "2", "--security", keys.string(), "--out", out.string()});
  const auto r = run_smart(secure, 60s, "secure_sharded", true);
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = last_json_line(r.out);
  EXPECT_GT(j["sim_handovers"].get<int>(), 0);
  EXPECT_TRUE(j["rejected_samples"].empty()) << j["rejected_samples"].dump();
  EXPECT_EQ(slurp(out / "robots.csv"), slurp(ref / "robots.csv"));
  for (const auto& d : {keys, ref, out}) std::filesystem::remove_all(d);
}

// A shard whose peer never comes up waits the join window (4 x --timeout-s), not --timeout-s,
// and says that the peer was never discovered (not stalled).
TEST_F(Sharded, AShardWithoutItsPeerGivesUpAfterTheJoinWindowSayingItWasNeverDiscovered) {
  const auto r =
      run_smart({"sim", "--map", (b_ / "maps/random-32-32-20.map").string(), "--scen",
                 (b_ / "scens/random-32-32-20-random-1.scen").string(), "--agents", "10", "--shard",
                 "1/2", "--timeout-s", "0.5", "--domain", std::to_string(kShardJoin)},
                30s, "shard_alone", true);
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_THAT(r.out, HasSubstr("shard 1: no exchange from shard(s) 0 for period 0 within 2.0"));
  EXPECT_THAT(r.out, HasSubstr("(0 of the 1 other shards' exchange writers discovered: a shard "
                               "not discovered is not running"));
}

TEST_F(Sharded, BadShardOptionsAreRefusedNamingTheFix) {
  const auto bad = run_smart({"sim", "--map", (b_ / "maps/random-32-32-20.map").string(), "--scen",
                              (b_ / "scens/random-32-32-20-random-1.scen").string(), "--shard",
                              "2/2", "--domain", std::to_string(kShardedBadInput)},
                             30s, "bad_shard", true);
  EXPECT_EQ(bad.code, 2);
  EXPECT_THAT(bad.out, HasSubstr("shard I (0 to N-1) of N"));
  auto args = run_args(plan("random-32-32-20.map", "random-32-32-20-random-1.scen",
                            "example_paths_xy.txt", "xy", "50"),
                       kShardedBadInput);
  args.insert(args.end(), {"--sim-hosts", "2", "--clock", "realtime"});
  const auto rt = run_smart(args, 30s, "bad_hosts", true);
  EXPECT_EQ(rt.code, 2);
  EXPECT_THAT(rt.out, HasSubstr("a sharded sim runs in lock-step"));
}

}  // namespace
}  // namespace smart::test
