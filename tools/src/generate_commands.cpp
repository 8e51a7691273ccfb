// `smart gen-map`, `smart gen-scen`, `smart plan`, `smart gen-walk`: a self-contained pipeline
// from nothing to an executable plan (no outside data needed).
#include <chrono>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "smart/grid/map_reader.hpp"
#include "smart/grid/scen_reader.hpp"
#include "smart/grid/text_file.hpp"
#include "smart/monitor/plan_validator.hpp"
#include "smart/planning/generators.hpp"
#include "smart/planning/lacam.hpp"
#include "smart/planning/pibt_plan.hpp"
#include "smart/planning/plan_lns.hpp"
#include "smart/planning/planner.hpp"
#include "smart/planning/random_plan.hpp"
#include "smart/tools/commands.hpp"

namespace smart::tools {

namespace {

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  if (!out || !(out << text)) {
    throw std::runtime_error("cannot write " + path + "; check the folder exists and is writable");
  }
}

struct WalkOptions {
  std::string map, out_plan, out_scen;
  planning::RandomPlanOptions walk;
};

// Conflict-free random walks of every robot (planning/random_plan.hpp): instances of any size at
// once, for scaling measurements where planning would take longer than the run.
int generate_walk(const WalkOptions& o) {
  const auto g = grid::parse_map(grid::read_text_file(o.map, "map"), o.map);
  auto inst = planning::generate_random_plan(g, o.walk);
  inst.scen.map_name = std::filesystem::path(o.map).filename().string();
  grid::throw_if_any(monitor::validate_plan(inst.plan, g, &inst.scen));
  write_file(o.out_plan, planning::to_smart_plan_text(inst.plan));
  write_file(o.out_scen, planning::to_movingai_scen(inst.scen, g));
  const auto st = grid::plan_stats(inst.plan);
  std::cout << nlohmann::json{{"plan", o.out_plan}, {"scen", o.out_scen},
                              {"axis", "xy"},       {"robots", st.robots},
                              {"soc", st.soc},      {"makespan", st.makespan},
                              {"moves", st.moves},  {"rotation_cycles", inst.rotation_cycles}}
                   .dump()
            << std::endl;
  return kExitSuccess;
}

void register_walk_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<WalkOptions>();
  auto* w = app.add_subcommand(
      "gen-walk",
      "Generate conflict-free random walks of N robots on a map (seeded; any size at once): a "
      "SMART timed plan (axis xy) and its scenario, for scaling runs");
  w->add_option("--map", o->map, "MovingAI .map file")->required();
  w->add_option("--robots,--agents", o->walk.robots, "number of robots")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1000000}))
      ->required();
  w->add_option("--steps", o->walk.steps, "timesteps of every walk")
      ->check(CLI::Range(std::size_t{1}, std::size_t{100000}))
      ->capture_default_str();
  w->add_option("--move-probability", o->walk.move_probability, "chance a robot moves per step")
      ->check(finite_in(0.0, 1.0))
      ->capture_default_str();
  w->add_option("--rotation-probability", o->walk.rotation_probability,
                "chance per step that four waiting robots round a 2x2 block rotate")
      ->check(finite_in(0.0, 1.0))
      ->capture_default_str();
  w->add_option("--seed", o->walk.seed, "random seed: the same seed makes the same walks")
      ->capture_default_str();
  w->add_option("--out", o->out_plan, "the plan file to write")->required();
  w->add_option("--out-scen", o->out_scen, "the scenario file to write")->required();
  w->callback([&exit_code, o] { exit_code = generate_walk(*o); });
}

struct PlanOptions {
  std::string map, scen, out;
  std::size_t agents = 0;
  uint64_t seed = 1;
  double time_limit_s = 120;
  PlanAlgorithm algorithm = PlanAlgorithm::kPrioritized;
  planning::PlanLnsOptions lns{.passes = 0};  // --lns-passes 0: the planner's plan as it is
};

const EnumNames<PlanAlgorithm> kPlanAlgorithmNames{{"pp", PlanAlgorithm::kPrioritized},
                                                   {"pibt", PlanAlgorithm::kPibt},
                                                   {"lacam", PlanAlgorithm::kLacam}};

}  // namespace

const EnumNames<MapKind> kMapKindNames{{"warehouse", MapKind::kWarehouse},
                                       {"random", MapKind::kRandom},
                                       {"empty", MapKind::kEmpty},
                                       {"maze", MapKind::kMaze}};

int generate_map(MapKind kind, const std::string& out, const GenMapOptionsPublic& o) {
  grid::Grid g;
  char blocked = '@';
  switch (kind) {
    case MapKind::kWarehouse:
      g = planning::generate_warehouse(o.warehouse);
      blocked = 'T';
      break;
    case MapKind::kRandom:
      g = planning::generate_random_map(o.width, o.height, o.obstacles, o.seed);
      break;
    case MapKind::kEmpty:
      g = planning::generate_empty_map(o.width, o.height);
      break;
    case MapKind::kMaze:
      g = planning::generate_maze(o.width, o.height, o.corridor, o.seed);
      break;
  }
  write_file(out, planning::to_movingai_map(g, blocked));
  std::cout << nlohmann::json{{"map", out},
                              {"kind", enum_name(kind, kMapKindNames)},
                              {"width", g.width()},
                              {"height", g.height()},
                              {"free_cells", g.free_cells()}}
                   .dump()
            << std::endl;
  return kExitSuccess;
}

int generate_scen(const std::string& map, std::size_t agents, uint64_t seed,
                  const std::string& out) {
  const auto g = grid::parse_map(grid::read_text_file(map, "map"), map);
  const auto name = std::filesystem::path(map).filename().string();
  const auto s = planning::generate_scenario(g, agents, seed, name);
  write_file(out, planning::to_movingai_scen(s, g));
  std::cout << nlohmann::json{{"scen", out}, {"agents", agents}, {"seed", seed}}.dump()
            << std::endl;
  return kExitSuccess;
}

namespace {

// The built-in planners' plans are per timestep from 0 (planner.hpp plan_from_timesteps): their
// cells are the timesteps' paths plan_lns.hpp takes.
planning::PlanLnsStats improve(const grid::Grid& g, planning::PlannerResult& r,
                               const planning::PlanLnsOptions& o) {
  auto paths = planning::timesteps_of(r.plan);
  planning::DistanceCache tables(g);
  const auto t0 = std::chrono::steady_clock::now();
  const auto st = planning::improve_plan(g, paths, tables, o);
  r.runtime_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.plan = planning::plan_from_timesteps(paths, r.plan.source);
  return st;
}

}  // namespace

int plan_instance(const std::string& map, const std::string& scen_file, std::size_t agents,
                  uint64_t seed, double time_limit_s, const std::string& out,
                  PlanAlgorithm algorithm, planning::PlanLnsOptions lns) {
  const auto g = grid::parse_map(grid::read_text_file(map, "map"), map);
  const auto scen =
      grid::parse_scen(grid::read_text_file(scen_file, "scenario"), scen_file, agents);
  grid::throw_if_any(grid::check_scen_against_map(scen, g));
  planning::PlannerResult r;
  if (algorithm == PlanAlgorithm::kPibt) {
    planning::PibtPlanOptions po;
    po.seed = seed;
    const auto t0 = std::chrono::steady_clock::now();
    r = planning::plan_pibt(g, scen, po);
    r.runtime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  } else if (algorithm == PlanAlgorithm::kLacam) {
    planning::LacamOptions lo;
    lo.seed = seed;
    lo.time_limit_s = time_limit_s;
    r = planning::plan_lacam(g, scen, lo);
  } else {
    planning::PlannerOptions po;
    po.seed = seed;
    po.time_limit_s = time_limit_s;
    r = planning::plan_prioritized(g, scen, po);
  }
  if (!r.solved) {
    std::cerr << "plan: no plan found: " << r.error
              << "; try another --seed, fewer --agents or a larger map\n";
    return kExitRunFailed;
  }
  const auto lns_st = lns.passes > 0 ? improve(g, r, lns) : planning::PlanLnsStats{};
  // The planner's output is checked like any other plan before it is written.
  grid::throw_if_any(monitor::validate_plan(r.plan, g, &scen));
  write_file(out, planning::to_smart_plan_text(r.plan));
  const auto st = grid::plan_stats(r.plan);
  std::cout << nlohmann::json{{"plan", out},
                              {"axis", "xy"},
                              {"robots", st.robots},
                              {"soc", st.soc},
                              {"makespan", st.makespan},
                              {"algorithm", enum_name(algorithm, kPlanAlgorithmNames)},
                              {"runtime_s", r.runtime_s},
                              {"restarts", r.restarts_used},
                              {"lns_passes", lns.passes},
                              {"lns_neighbourhood", lns.neighbourhood},
                              {"lns_expansions", lns.max_expansions},
                              {"lns_improved", lns_st.improved},
                              {"lns_saved", lns_st.saved}}
                   .dump()
            << std::endl;
  return kExitSuccess;
}

namespace {

// `smart gen-map KIND`: a seeded MovingAI map.
void register_gen_map_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<GenMapOptionsPublic>();
  auto kind = std::make_shared<MapKind>(MapKind::kWarehouse);
  auto out = std::make_shared<std::string>();
  auto* gm = app.add_subcommand("gen-map", "Generate a MovingAI map (seeded)");
  add_enum_option(gm, "kind", *kind, kMapKindNames, "the kind of map")->required();
  gm->add_option("--out", *out, "the .map file to write")->required();
  gm->add_option("--width", o->width, "map width in cells (columns)")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  gm->add_option("--height", o->height, "map height in cells (rows)")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  gm->add_option("--obstacles", o->obstacles, "random: obstacle probability")
      ->check(finite_in(0.0, 0.9))
      ->capture_default_str();
  gm->add_option("--corridor", o->corridor, "maze: corridor width")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  gm->add_option("--seed", o->seed, "random seed: the same seed makes the same map")
      ->capture_default_str();
  gm->add_option("--shelf-rows", o->warehouse.shelf_rows, "warehouse: rows of shelf blocks")
      ->capture_default_str();
  gm->add_option("--shelf-cols", o->warehouse.shelf_cols, "warehouse: columns of shelf blocks")
      ->capture_default_str();
  gm->add_option("--shelf-length", o->warehouse.shelf_length,
                 "warehouse: cells per shelf block, along a row")
      ->capture_default_str();
  gm->add_option("--shelf-height", o->warehouse.shelf_height,
                 "warehouse: cells per shelf block, across rows")
      ->capture_default_str();
  gm->add_option("--aisle", o->warehouse.aisle, "warehouse: aisle width in cells between blocks")
      ->capture_default_str();
  gm->add_option("--margin", o->warehouse.margin, "warehouse: free cells around the shelf area")
      ->capture_default_str();
  gm->callback([&exit_code, o, kind, out] { exit_code = generate_map(*kind, *out, *o); });
}

// `smart gen-scen`: a seeded MovingAI scenario for a map.
void register_gen_scen_command(CLI::App& app, int& exit_code) {
  auto so = std::make_shared<PlanOptions>();
  auto* gs = app.add_subcommand("gen-scen", "Generate a MovingAI scenario for a map (seeded)");
  gs->add_option("--map", so->map, "the MovingAI .map the agents stand on")->required();
  gs->add_option("--agents,--robots", so->agents, "number of robots (distinct starts and goals)")
      ->required()
      ->check(CLI::Range(1ul, 1000000ul));
  gs->add_option("--seed", so->seed, "random seed: the same seed makes the same scenario")
      ->capture_default_str();
  gs->add_option("--out", so->out, "the .scen file to write")->required();
  gs->callback(
      [&exit_code, so] { exit_code = generate_scen(so->map, so->agents, so->seed, so->out); });
}

// `smart plan`: a plan from one of the built-in planners, checked before it is written.
void register_plan_command(CLI::App& app, int& exit_code) {
  auto po = std::make_shared<PlanOptions>();
  auto* pl = app.add_subcommand(
      "plan",
      "Plan conflict-free paths (prioritized planning with space-time A*, PIBT or LaCAM); writes a "
      "SMART timed plan (axis xy) that passes `smart check-plan`");
  pl->add_option("--map", po->map, "MovingAI .map file")->required();
  pl->add_option("--scen", po->scen, "MovingAI .scen file (starts and goals)")->required();
  pl->add_option("--agents,--robots", po->agents, "first N robots (default: all)")
      ->check(CLI::PositiveNumber);
  add_enum_option(pl, "--algorithm", po->algorithm, kPlanAlgorithmNames,
                  "pp: prioritized planning, short plans (planner.hpp); pibt: PIBT alone, "
                  "LaCAM's configuration generator, long plans with waits (pibt_plan.hpp); "
                  "lacam: LaCAM's search over PIBT steps, complete where PIBT alone cycles "
                  "(lacam.hpp)");
  pl->add_option("--seed", po->seed, "seed for priority orders (pp: after a failure)")
      ->capture_default_str();
  pl->add_option("--time-limit-s", po->time_limit_s, "give up after this many wall seconds")
      ->check(finite_in(0.001, 1e6))
      ->capture_default_str();
  pl->add_option("--lns-passes", po->lns.passes,
                 "then rounds of replanning each robot by space-time A* against the others' "
                 "paths, kept when it arrives earlier (MAPF-LNS with neighbourhoods of one robot, "
                 "plan_lns.hpp); 0: the planner's plan as it is")
      ->check(CLI::Range(0, 16))
      ->capture_default_str();
  pl->add_option("--lns-neighbourhood", po->lns.neighbourhood,
                 "robots each LNS step replans together: the most delayed robot and the robots "
                 "in the way of its shortest path, kept when their arrivals sum lower; when they "
                 "do not, the robot alone (MAPF-LNS's agent-based neighbourhood, plan_lns.hpp)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  pl->add_option("--lns-expansions", po->lns.max_expansions,
                 "A* expansions a replanned robot may take before its path is kept; long plans "
                 "of crowded maps gain from more (docs/execution.md)")
      ->check(CLI::Range(std::size_t{100}, std::size_t{100'000'000}))
      ->capture_default_str();
  pl->add_option("--out", po->out, "the plan file to write")->required();
  pl->callback([&exit_code, po] {
    exit_code = plan_instance(po->map, po->scen, po->agents, po->seed, po->time_limit_s, po->out,
                              po->algorithm, po->lns);
  });
}

}  // namespace

void register_generate_commands(CLI::App& app, int& exit_code) {
  register_walk_command(app, exit_code);
  register_gen_map_command(app, exit_code);
  register_gen_scen_command(app, exit_code);
  register_plan_command(app, exit_code);
}

}  // namespace smart::tools
