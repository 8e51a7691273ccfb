// `smart demo`: the default job run by `make demo`, self-contained: generate a warehouse map
// and a 100-robot scenario, plan them with the built-in planner, execute the plan on the
// simulated fleet over DDS (`smart run`), and print the summary.
#include <iostream>

#include "smart/common/child_process.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"

namespace smart::tools {

void register_demo_command(CLI::App& app, int& exit_code) {
  struct DemoOptions {
    int domain = 42;
    std::size_t robots = 100;
    std::string out = "demo-out";
    uint64_t seed = 1;
  };
  auto o = std::make_shared<DemoOptions>();
  auto* demo = app.add_subcommand("demo",
                                  "Generate a warehouse, plan ~100 robots, execute the "
                                  "plan on the simulated fleet, print the summary");
  demo->add_option("--domain", o->domain, "DDS domain id (0-230)")
      ->envname("SMART_DOMAIN")  // as every other command (it ignored it: issue 26)
      ->check(CLI::Range(0, 230))
      ->capture_default_str();
  demo->add_option("--robots,--agents", o->robots, "robots in the generated scenario")
      ->capture_default_str();
  demo->add_option("--out", o->out, "folder for the generated files and results")
      ->capture_default_str();
  demo->add_option("--seed", o->seed, "seed of the scenario and the planner (printed)")
      ->capture_default_str();
  demo->callback([&exit_code, o] {
    install_stop_handlers();
    std::filesystem::create_directories(o->out);
    const auto dir = std::filesystem::path(o->out);
    const auto map = (dir / "warehouse.map").string();
    const auto scen = (dir / "warehouse.scen").string();
    const auto plan = (dir / "warehouse.plan").string();
    std::cerr
        << "demo: 1/4 generating a warehouse map (the MovingAI warehouse-10-20-10-2-1 layout)\n";
    GenMapOptionsPublic gm;
    if ((exit_code = generate_map(MapKind::kWarehouse, map, gm)) != 0) return;
    std::cerr << "demo: 2/4 generating a scenario with " << o->robots << " robots (seed " << o->seed
              << ")\n";
    if ((exit_code = generate_scen(map, o->robots, o->seed, scen)) != 0) return;
    std::cerr << "demo: 3/4 planning with the built-in prioritized planner\n";
    if ((exit_code = plan_instance(map, scen, o->robots, o->seed, 120, plan)) != 0) return;
    std::cerr << "demo: 4/4 executing the plan: monitor + Simbody sim host over DDS\n";
    common::ChildProcess run({common::self_executable().string(), "run", "--map", map, "--scen",
                              scen, "--plan", plan, "--axis", "xy", "--domain",
                              std::to_string(o->domain), "--out", (dir / "results").string()});
    exit_code = run.wait(std::chrono::hours(1)).value_or(124);
    std::cerr << "demo: results in " << (dir / "results").string() << "\n"
              << "demo: watch it in the viewer: " << common::self_executable().string()
              << " serve --open " << std::filesystem::absolute(dir / "results").string()
              << "   then open http://127.0.0.1:8080/\n";
  });
}

}  // namespace smart::tools
