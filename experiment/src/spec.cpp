#include "smart/experiment/spec.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <filesystem>
#include <optional>
#include <set>
#include <stdexcept>
#include <tuple>
#include <type_traits>
#include <utility>

#include "smart/monitor/results_format.hpp"

namespace smart::experiment {

namespace {
using nlohmann::json;

[[noreturn]] void fail(const std::string& source, const YAML::Node& at, const std::string& field,
                       const std::string& what) {
  const int line = at.Mark().line >= 0 ? at.Mark().line + 1 : 0;
  throw std::invalid_argument(source + ":" + std::to_string(line) + ": " + field + ": " + what);
}

bool plain_name(const std::string& s) {
  return !s.empty() && s.size() <= 64 &&
         s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-") ==
             std::string::npos;
}

// A margin in a folder name: the shortest decimal that reads back as it ("0.5", "10"), so two
// margins never share a folder (six significant digits did).
std::string compact(double v) {
  std::array<char, 32> buf{};
  const auto end = std::to_chars(buf.data(), buf.data() + buf.size(), v).ptr;
  return {buf.data(), end};
}

// An axis lists each value once. A repeat (or, for robots and qos, another file of the same stem,
// which names their folders) would run the first value's cells again, into the same folders.
void once(std::set<std::string>& seen, const std::string& name, const YAML::Node& at,
          const std::string& src, const std::string& field) {
  if (!seen.insert(name).second) {
    fail(src, at, field,
         "'" + name + "' is listed twice; list each value once (a repeat runs the same cells)");
  }
}

// What a list's values must not repeat: nothing (maps: one per scen), the value, or its file stem.
enum class Distinct { kNo, kValue, kStem };

// A list of strings (a single string is a list of one); `fallback` when the key is absent.
std::vector<std::string> strings(const YAML::Node& root, const char* key, const std::string& src,
                                 std::vector<std::string> fallback, Distinct distinct) {
  const auto n = root[key];
  if (!n) {
    if (fallback.empty()) fail(src, root, key, "missing; give a list, e.g. [a, b]");
    return fallback;
  }
  std::vector<std::string> out;
  std::set<std::string> seen;
  try {
    if (n.IsScalar()) return {n.as<std::string>()};
    for (const auto& v : n) {
      out.push_back(v.as<std::string>());
      if (distinct == Distinct::kNo) continue;
      const auto stem = std::filesystem::path(out.back()).stem().string();
      once(seen, distinct == Distinct::kStem ? stem : out.back(), v, src, key);
    }
  } catch (const YAML::Exception&) {
    fail(src, n, key, "expected a list of names, e.g. [a, b]");
  }
  if (out.empty()) fail(src, n, key, "is empty; give at least one");
  return out;
}

// A list of whole numbers from lo to hi (a single number is a list of one) at `n`, `range` saying
// what they are when one is out of range.
std::vector<long long> whole_numbers(const YAML::Node& n, const std::string& src,
                                     const std::string& field, long long lo, long long hi,
                                     const std::string& range) {
  YAML::Node list(YAML::NodeType::Sequence);
  if (n.IsSequence()) {
    list = n;
  } else {
    list.push_back(n);
  }
  std::vector<long long> out;
  std::set<std::string> seen;
  for (const auto& v : list) {
    long long k = 0;
    try {
      k = v.as<long long>();
    } catch (const YAML::Exception&) {
      fail(src, v, field, "'" + v.as<std::string>("?") + "' is not a whole number");
    }
    if (k < lo || k > hi) fail(src, v, field, std::to_string(k) + " is out of range: " + range);
    once(seen, std::to_string(k), v, src, field);
    out.push_back(k);
  }
  return out;
}

std::vector<std::size_t> counts(const YAML::Node& root, const std::string& src) {
  const auto n = root["agents"];
  if (!n) fail(src, root, "agents", "missing; give fleet sizes, e.g. [10, 100]");
  std::vector<std::size_t> out;
  for (const auto k :
       whole_numbers(n, src, "agents", 1, 100000, "fleet sizes run from 1 to 100000")) {
    out.push_back(static_cast<std::size_t>(k));
  }
  if (out.empty()) fail(src, n, "agents", "is empty; give at least one fleet size");
  return out;
}

PlanSpec read_one_plan(const YAML::Node& p, const std::string& src, const std::string& field,
                       std::size_t index) {
  if (!p || !p.IsMap()) {
    fail(src, p, field,
         "give {file: paths.txt, axis: xy}, {planner: builtin} or {command: \"... {plan}\"}");
  }
  const int given = (p["file"] ? 1 : 0) + (p["planner"] ? 1 : 0) + (p["command"] ? 1 : 0);
  if (given != 1) fail(src, p, field, "give exactly one of file, planner and command");
  if (p["algorithm"] && !p["planner"]) {
    fail(src, p["algorithm"], field + ".algorithm", "only {planner: builtin} takes an algorithm");
  }
  if (p["lns_passes"] && (!p["planner"] || !p["lns_passes"].IsScalar())) {
    fail(src, p["lns_passes"], field + ".lns_passes",
         "only {planner: builtin} takes it, one whole number, e.g. 4");
  }
  for (const char* key : {"lns_neighbourhood", "lns_expansions"}) {
    if (p[key] && (!p["lns_passes"] || !p[key].IsScalar())) {
      fail(src, p[key], field + "." + key, "only with lns_passes, one whole number, e.g. 8");
    }
  }
  PlanSpec plan;
  if (p["file"]) {
    plan.source = PlanSource::kFile, plan.text = p["file"].as<std::string>();
    plan.name = std::filesystem::path(plan.text).stem().string();
  } else if (p["planner"]) {
    if (p["planner"].as<std::string>() != "builtin") {
      fail(src, p["planner"], field + ".planner", "the only planner inside is 'builtin'");
    }
    plan.source = PlanSource::kBuiltin, plan.name = "builtin";
    if (p["algorithm"]) {
      plan.algorithm = p["algorithm"].as<std::string>();
      if (plan.algorithm != "pp" && plan.algorithm != "pibt" && plan.algorithm != "lacam") {
        fail(src, p["algorithm"], field + ".algorithm",
             "pp (prioritized planning), pibt or lacam (`smart plan --algorithm`)");
      }
      plan.name = "builtin-" + plan.algorithm;
    }
    if (p["lns_passes"]) {
      plan.lns_passes = static_cast<int>(
          whole_numbers(p["lns_passes"], src, field + ".lns_passes", 0, 16, "rounds run 0-16")
              .at(0));
    }
    if (p["lns_neighbourhood"]) {
      plan.lns_neighbourhood =
          static_cast<int>(whole_numbers(p["lns_neighbourhood"], src, field + ".lns_neighbourhood",
                                         1, 64, "robots replanned together, 1-64")
                               .at(0));
    }
    if (p["lns_expansions"]) {
      plan.lns_expansions = whole_numbers(p["lns_expansions"], src, field + ".lns_expansions", 100,
                                          100'000'000, "A* expansions a robot, 100-100000000")
                                .at(0);
    }
  } else {
    plan.source = PlanSource::kCommand, plan.text = p["command"].as<std::string>();
    plan.name = field == "plan" ? "command" : "command" + std::to_string(index);
    if (plan.text.find("{plan}") == std::string::npos) {
      fail(src, p["command"], field + ".command", "must write {plan} (the file it is given)");
    }
  }
  if (p["name"]) plan.name = p["name"].as<std::string>();
  if (!plain_name(plan.name)) {
    fail(src, p["name"] ? p["name"] : p, field + ".name", "1-64 of A-Z a-z 0-9 . _ -");
  }
  plan.axis = p["axis"] ? p["axis"].as<std::string>() : "xy";
  if (plan.axis != "xy" && plan.axis != "rowcol") {
    fail(src, p["axis"], field + ".axis", "xy or rowcol");
  }
  return plan;
}

// plan: one source, or plans: a planner axis of several, each named once.
void read_plan(const YAML::Node& root, const std::string& src, Spec& s) {
  if (root["plan"] && root["plans"]) {
    fail(src, root["plans"], "plans", "give plan (one) or plans (a list), not both");
  }
  if (!root["plans"]) {
    s.plans = {read_one_plan(root["plan"], src, "plan", 0)};
    return;
  }
  const auto list = root["plans"];
  if (!list.IsSequence() || list.size() == 0) {
    fail(src, list, "plans", "a list of plan sources, e.g. [{planner: builtin}]");
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    s.plans.push_back(read_one_plan(list[i], src, "plans[" + std::to_string(i) + "]", i));
    if (!names.insert(s.plans.back().name).second) {
      fail(src, list[i], "plans[" + std::to_string(i) + "].name",
           "'" + s.plans.back().name + "' names two plan sources; give each its own name");
    }
  }
}

void read_instances(const YAML::Node& root, const std::string& src, Spec& s) {
  const auto maps = strings(root, "maps", src, {}, Distinct::kNo);
  const auto scens = strings(root, "scens", src, {}, Distinct::kValue);
  if (maps.size() != 1 && maps.size() != scens.size()) {
    fail(src, root["maps"], "maps",
         "give one map for every scen, or one map per scen (as many maps as scens)");
  }
  for (std::size_t i = 0; i < scens.size(); ++i) {
    s.instances.emplace_back(maps.size() == 1 ? maps[0] : maps[i], scens[i]);
  }
}

// Uncertainty keys and their ranges (agent/robot_model.cpp reads the same in robot YAML).
// LoRR-style delay events (agent/uncertainty.hpp) as `smart run` takes them.
const std::vector<std::tuple<std::string, double, double>> kUncertaintyKeys{
    {"stall_probability", 0.0, 1.0}, {"stall_s", 0.0, 3600.0},        {"speed_sigma", 0.0, 1.0},
    {"slip_sigma", 0.0, 0.5},        {"delay_probability", 0.0, 1.0}, {"delay_rate_hz", 0.0, 10.0},
    {"delay_min_s", 0.0, 3600.0},    {"delay_max_s", 0.0, 3600.0}};

void read_uncertainty(const YAML::Node& root, const std::string& src, Spec& s) {
  const auto list = root["uncertainty"];
  if (!list) return;
  if (!list.IsSequence() || list.size() == 0) {
    fail(src, list, "uncertainty", "a list of settings, e.g. [{}, {stall_probability: 0.05}]");
  }
  s.uncertainty.clear();
  std::set<std::string> seen;
  for (const auto& entry : list) {
    if (!entry.IsMap()) fail(src, entry, "uncertainty", "each entry is a mapping, e.g. {}");
    json u = json::object();
    for (const auto& kv : entry) {
      const auto key = kv.first.as<std::string>();
      const auto it = std::find_if(kUncertaintyKeys.begin(), kUncertaintyKeys.end(),
                                   [&](const auto& k) { return std::get<0>(k) == key; });
      if (it == kUncertaintyKeys.end()) {
        fail(src, kv.first, "uncertainty." + key,
             "unknown; use stall_probability, stall_s, speed_sigma, slip_sigma, "
             "delay_probability, delay_rate_hz, delay_min_s, delay_max_s");
      }
      double v = -1;
      try {
        v = kv.second.as<double>();
      } catch (const YAML::Exception&) {
      }
      if (!(v >= std::get<1>(*it) && v <= std::get<2>(*it))) {
        fail(src, kv.second, "uncertainty." + key,
             "a number from " + json(std::get<1>(*it)).dump() + " to " +
                 json(std::get<2>(*it)).dump());
      }
      u[key] = v;
    }
    once(seen, u.dump(), entry, src, "uncertainty");
    s.uncertainty.push_back(u);
  }
}

// The switching knobs, the executions that read each (`smart run` refuses it for the others),
// and what a spec whose executions read none of it is told.
struct KnobReaders {
  std::string_view field;
  std::vector<std::string_view> executions;
  std::string_view hint;
};
const std::vector<KnobReaders>& knob_readers() {
  static const std::vector<KnobReaders> k{
      {"switch_lookahead_actions",
       {"switchable-lookahead"},
       "only switchable-lookahead takes it; add it to executions"},
      {"switch_window_pairs",
       {"switchable-lookahead"},
       "only switchable-lookahead takes it; add it to executions"},
      {"switch_margin_s",
       {"switchable-opt", "switchable-lookahead"},
       "only switchable-opt and switchable-lookahead take it; add one of them to executions"},
      {"switch_horizon_actions",
       {"switchable-opt", "switchable-lookahead"},
       "only switchable-opt and switchable-lookahead take it; add one of them to executions"},
  };
  return k;
}
const KnobReaders kEverySwitchingExecution{
    "",
    {"switchable", "switchable-opt", "switchable-lookahead"},
    "only the switching executions take it; add switchable (or switchable-opt) to executions"};

const KnobReaders& readers_of(std::string_view field) {
  const auto& k = knob_readers();
  const auto it = std::ranges::find(k, field, &KnobReaders::field);
  return it == k.end() ? kEverySwitchingExecution : *it;
}

bool reads_knob(const std::string& execution, std::string_view field) {
  return std::ranges::count(readers_of(field).executions, execution) > 0;
}

// A switching axis must have an execution of the spec that reads it.
void needs_a_reader(const YAML::Node& n, const std::string& src, const Spec& s,
                    const std::string& field) {
  if (!std::ranges::any_of(s.executions, [&](const auto& e) { return reads_knob(e, field); })) {
    fail(src, n, field, std::string(readers_of(field).hint));
  }
}

// A switching axis of whole numbers from `lo` (1 unless told) to `hi` (smart run's range);
// `example` shows a list.
std::vector<uint32_t> read_switching_axis(const YAML::Node& root, const std::string& src,
                                          const Spec& s, const std::string& field, long long hi,
                                          const std::string& range, const std::string& example,
                                          long long lo = 1) {
  const auto n = root[field];
  std::vector<uint32_t> out;
  if (!n) return out;
  for (const auto k : whole_numbers(n, src, field, lo, hi, range)) {
    out.push_back(static_cast<uint32_t>(k));
  }
  if (out.empty()) fail(src, n, field, "is empty; give at least one, e.g. " + example);
  needs_a_reader(n, src, s, field);
  return out;
}

double number_in(const YAML::Node& n, const std::string& src, const std::string& field, double lo,
                 double hi) {
  double v = -1;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
  }
  if (!(v >= lo && v <= hi)) {
    fail(src, n, field,
         "'" + n.as<std::string>("?") + "' is not a number from " + json(lo).dump() + " to " +
             json(hi).dump());
  }
  return v;
}

// An axis of numbers from lo to hi (a single number is a list of one), each listed once.
std::vector<double> numbers(const YAML::Node& n, const std::string& src, const std::string& field,
                            double lo, double hi) {
  if (!n.IsSequence()) return {number_in(n, src, field, lo, hi)};
  std::vector<double> out;
  std::set<std::string> seen;
  for (const auto& v : n) {
    out.push_back(number_in(v, src, field, lo, hi));
    once(seen, compact(out.back()), v, src, field);
  }
  return out;
}

// The commit distance, chains and anticipation's knobs.
void read_switching_axes(const YAML::Node& root, const std::string& src, Spec& s) {
  s.switch_commit_actions = read_switching_axis(root, src, s, "switch_commit_actions", 1000,
                                                "from 1 to 1000 actions", "[2, 6]");
  s.switch_chain_locations = read_switching_axis(root, src, s, "switch_chain_locations", 64,
                                                 "from 1 to 64 locations", "[1, 8]");
  s.switch_horizon_actions = read_switching_axis(root, src, s, "switch_horizon_actions", 1000,
                                                 "from 1 to 1000 actions", "[12, 24]");
  s.switch_lookahead_actions = read_switching_axis(root, src, s, "switch_lookahead_actions", 1000,
                                                   "from 1 to 1000 actions", "[24, 48]");
  s.switch_window_pairs = read_switching_axis(root, src, s, "switch_window_pairs", 6,
                                              "from 0 (off) to 6 pairs", "[0, 3]", 0);
  if (const auto n = root["switch_margin_s"]) {
    const std::string field = "switch_margin_s";
    s.switch_margin_s = numbers(n, src, field, 0, 3600);
    if (s.switch_margin_s.empty()) fail(src, n, field, "is empty; give at least one, e.g. [1, 10]");
    needs_a_reader(n, src, s, field);
  }
}

void read_options(const YAML::Node& root, const std::string& src, Spec& s) {
  s.robots = strings(root, "robots", src, {"footbot"}, Distinct::kStem);
  s.qos = strings(root, "qos", src, {"lan"}, Distinct::kStem);
  s.executions = strings(root, "executions", src, {"adg"}, Distinct::kValue);
  for (const auto& e : s.executions) {
    if (e != "adg" && e != "switchable" && e != "switchable-opt" && e != "switchable-lookahead")
      fail(src, root["executions"], "executions",
           "adg, switchable, switchable-opt or switchable-lookahead");
  }
  read_switching_axes(root, src, s);
  if (root["clock"]) s.clock = root["clock"].as<std::string>();
  if (s.clock != "lockstep" && s.clock != "realtime") {
    fail(src, root["clock"], "clock", "lockstep or realtime");
  }
  if (const auto r = root["repeats"]) {
    long long k = 0;
    try {
      k = r.as<long long>();
    } catch (const YAML::Exception&) {
      fail(src, r, "repeats", "expected a whole number");
    }
    if (k < 1 || k > 1000) fail(src, r, "repeats", "from 1 to 1000");
    s.repeats = static_cast<std::size_t>(k);
  }
  if (const auto r = root["state_rate_hz"]) {
    s.state_rate_hz = number_in(r, src, "state_rate_hz", 0, 1000);
  }
  for (const auto& kv : root) {
    static const std::set<std::string> known{"name",
                                             "maps",
                                             "scens",
                                             "agents",
                                             "plan",
                                             "plans",
                                             "robots",
                                             "qos",
                                             "clock",
                                             "repeats",
                                             "uncertainty",
                                             "lifelong",
                                             "planners",
                                             "executions",
                                             "switch_commit_actions",
                                             "switch_chain_locations",
                                             "switch_margin_s",
                                             "switch_horizon_actions",
                                             "switch_lookahead_actions",
                                             "switch_window_pairs",
                                             "state_rate_hz"};
    const auto key = kv.first.as<std::string>();
    if (!known.count(key)) {
      fail(src, kv.first, key,
           "unknown field; the fields are name, maps, scens, agents, plan or plans, robots, qos, "
           "clock, uncertainty, executions, switch_commit_actions, switch_chain_locations, "
           "switch_margin_s, switch_horizon_actions, switch_lookahead_actions, "
           "switch_window_pairs, repeats, state_rate_hz "
           "(lifelong: lifelong, agents, planners)");
    }
  }
}

// planners: [{planner: builtin}, {name: x, command: "..."}] (a lifelong run's --planner-cmd).
void read_lifelong_planners(const YAML::Node& root, const std::string& src, Spec& s) {
  const auto list = root["planners"];
  if (!list) {
    s.plans = {{"builtin", PlanSource::kBuiltin, "", "xy"}};
    return;
  }
  if (!list.IsSequence() || list.size() == 0) {
    fail(src, list, "planners", "a list, e.g. [{planner: builtin}, {command: \"python3 p.py\"}]");
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const auto field = "planners[" + std::to_string(i) + "]";
    const auto p = list[i];
    if (!p.IsMap() || (p["planner"] ? 1 : 0) + (p["command"] ? 1 : 0) != 1) {
      fail(src, p, field,
           "give {planner: builtin} or {command: \"...\"} (with a name: if you like)");
    }
    if (p["planner"] && p["planner"].as<std::string>("") != "builtin") {
      fail(src, p["planner"], field + ".planner", "the only planner inside is 'builtin'");
    }
    PlanSpec plan{p["planner"] ? "builtin" : "command" + std::to_string(i),
                  p["planner"] ? PlanSource::kBuiltin : PlanSource::kCommand,
                  p["command"] ? p["command"].as<std::string>() : "", "xy"};
    if (p["window_lns_passes"]) {
      if (!p["planner"] || !p["window_lns_passes"].IsScalar()) {
        fail(src, p["window_lns_passes"], field + ".window_lns_passes",
             "only {planner: builtin} takes it, one whole number, e.g. 1");
      }
      plan.lns_passes =
          static_cast<int>(whole_numbers(p["window_lns_passes"], src, field + ".window_lns_passes",
                                         0, 16, "rounds run from 0 to 16")
                               .at(0));
    }
    if (p["name"]) plan.name = p["name"].as<std::string>("");
    if (!plain_name(plan.name)) fail(src, p, field + ".name", "1-64 of A-Z a-z 0-9 . _ -");
    if (!names.insert(plan.name).second) {
      fail(src, p, field + ".name", "'" + plan.name + "' names two planners; name each once");
    }
    s.plans.push_back(plan);
  }
}

void read_lifelong(const YAML::Node& root, const std::string& src, Spec& s) {
  const auto l = root["lifelong"];
  if (!l.IsMap()) fail(src, l, "lifelong", "a mapping: {map: M.map, duration_s: 60}");
  for (const char* key : {"maps", "scens", "plan", "plans"}) {
    if (root[key]) {
      fail(src, root[key], key,
           "a lifelong experiment has no plan files: its map is lifelong.map (or "
           "lifelong.problem) and its planners are planners:");
    }
  }
  if (!root["planners"] && root["plans"]) fail(src, root["plans"], "plans", "use planners:");
  LifelongSpec ls;
  for (const auto& kv : l) {
    const auto key = kv.first.as<std::string>();
    const auto field = "lifelong." + key;
    if (key == "map" || key == "problem") {
      (key == "map" ? ls.map : ls.problem) = kv.second.as<std::string>("");
    } else if (key == "duration_s") {
      ls.duration_s = number_in(kv.second, src, field, 0.1, 1e7);
    } else if (key == "task_errands") {
      ls.task_errands = static_cast<int>(number_in(kv.second, src, field, 1, 64));
    } else if (key == "replan_period_s") {
      ls.replan_period_s = numbers(kv.second, src, field, 0.05, 3600);
      if (ls.replan_period_s.empty()) fail(src, kv.second, field, "give at least one period");
    } else if (key == "lookahead") {
      ls.lookahead.clear();
      for (const auto k : whole_numbers(kv.second, src, field, 1, 1000, "from 1 to 1000 actions")) {
        ls.lookahead.push_back(static_cast<uint32_t>(k));
      }
      if (ls.lookahead.empty()) fail(src, kv.second, field, "give at least one, e.g. [4, 8]");
    } else {
      fail(src, kv.first, field,
           "unknown; the fields are map or problem, duration_s, task_errands, replan_period_s, "
           "lookahead");
    }
  }
  if (ls.map.empty() == ls.problem.empty()) {
    fail(src, l, "lifelong", "give map (random tasks on it) or problem (a LoRR problem), one");
  }
  if (!ls.problem.empty() && root["agents"]) {
    fail(src, root["agents"], "agents", "a LoRR problem brings its team; drop agents");
  }
  s.instances = {{ls.map.empty() ? ls.problem : ls.map, ""}};
  s.agents = ls.problem.empty() ? counts(root, src) : std::vector<std::size_t>{0};
  s.lifelong = ls;
  read_lifelong_planners(root, src, s);
}

std::string stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

// A plan run's scen names its instance; a lifelong run's map or problem does.
std::string instance_stem(const Spec& s, std::size_t i) {
  return stem(s.lifelong ? s.instances[i].first : s.instances[i].second);
}

std::size_t periods(const Spec& s) { return s.lifelong ? s.lifelong->replan_period_s.size() : 1; }

// The commit cut's look-aheads of a lifelong grid (0: smart run's default, the flag not given).
std::vector<uint32_t> lookaheads(const Spec& s) {
  if (!s.lifelong || s.lifelong->lookahead.empty()) return {0};
  return s.lifelong->lookahead;
}

void flatten(const json& j, const std::string& prefix, json& row) {
  for (const auto& [k, v] : j.items()) {
    const auto name = prefix.empty() ? k : prefix + "." + k;
    if (v.is_object()) {
      flatten(v, name, row);
    } else {
      row[name] = v.is_array() ? json(v.dump()) : v;
    }
  }
}

std::string csv_field(const json& v) {
  std::string s = v.is_string() ? v.get<std::string>() : v.is_null() ? "" : v.dump();
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

const std::vector<std::string> kParams{"cell",
                                       "map",
                                       "scen",
                                       "agents",
                                       "robot",
                                       "qos",
                                       "uncertainty",
                                       "repeat",
                                       "plan",
                                       "axis",
                                       "clock",
                                       "execution",
                                       "switch_commit_actions",
                                       "switch_chain_locations",
                                       "switch_margin_s",
                                       "switch_horizon_actions",
                                       "switch_lookahead_actions",
                                       "switch_window_pairs",
                                       "replan_period_s",
                                       "lookahead",
                                       "planner_runtime_s"};
}  // namespace

Spec parse_spec(std::string_view text, const std::string& src) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(src + ":" + std::to_string(e.mark.line + 1) +
                                ": not YAML: " + e.msg);
  }
  if (!root.IsMap()) throw std::invalid_argument(src + ": expected a YAML mapping (name: ...)");
  Spec s;
  s.name = root["name"] ? root["name"].as<std::string>() : "";
  if (!plain_name(s.name)) {
    fail(src, root["name"] ? root["name"] : root, "name", "1-64 of A-Z a-z 0-9 . _ -");
  }
  if (root["lifelong"]) {
    read_lifelong(root, src, s);
  } else {
    if (root["planners"]) fail(src, root["planners"], "planners", "only with lifelong:");
    read_instances(root, src, s);
    s.agents = counts(root, src);
    read_plan(root, src, s);
  }
  read_options(root, src, s);
  read_uncertainty(root, src, s);
  return s;
}

namespace {

// One setting of the switching knobs an execution runs with; 0 or none: the flag not given.
struct Knobs {
  uint32_t commit = 0, chain = 0;
  std::optional<double> margin_s;
  uint32_t horizon = 0, reach = 0;
  std::optional<uint32_t> window;
};

// The knob settings of an execution: the product of the axes it reads (plain ADG reads none).
std::vector<Knobs> switching_axis(const Spec& s, const std::string& e) {
  const auto read = [&e](const auto& axis, std::string_view field) {
    using V = typename std::decay_t<decltype(axis)>::value_type;
    std::vector<std::optional<V>> out(axis.begin(), axis.end());
    if (out.empty() || !reads_knob(e, field)) out = {std::nullopt};
    return out;
  };
  std::vector<Knobs> axis;
  for (const auto commit : read(s.switch_commit_actions, "switch_commit_actions")) {
    for (const auto chain : read(s.switch_chain_locations, "switch_chain_locations")) {
      for (const auto margin : read(s.switch_margin_s, "switch_margin_s")) {
        for (const auto horizon : read(s.switch_horizon_actions, "switch_horizon_actions")) {
          for (const auto reach : read(s.switch_lookahead_actions, "switch_lookahead_actions")) {
            for (const auto window : read(s.switch_window_pairs, "switch_window_pairs")) {
              axis.push_back({commit.value_or(0), chain.value_or(0), margin, horizon.value_or(0),
                              reach.value_or(0), window});
            }
          }
        }
      }
    }
  }
  return axis;
}

// The folder name's part for the knobs given; none for plain ADG (its folders stay as they were).
std::string knobs_key(const std::string& e, const Knobs& k) {
  std::string key = e == "adg" ? "" : "-" + e;
  if (k.commit != 0) key += "-c" + std::to_string(k.commit);
  if (k.chain != 0) key += "-k" + std::to_string(k.chain);
  if (k.margin_s) key += "-m" + compact(*k.margin_s);
  if (k.horizon != 0) key += "-h" + std::to_string(k.horizon);
  if (k.reach != 0) key += "-a" + std::to_string(k.reach);
  if (k.window) key += "-w" + std::to_string(*k.window);
  return key;
}

}  // namespace

std::vector<Cell> expand(const Spec& s) {
  std::vector<Cell> cells;
  for (std::size_t i = 0; i < s.instances.size(); ++i) {
    for (const auto n : s.agents) {
      for (std::size_t p = 0; p < s.plans.size(); ++p) {
        for (const auto& robot : s.robots) {
          for (const auto& qos : s.qos) {
            for (std::size_t u = 0; u < s.uncertainty.size(); ++u) {
              for (std::size_t t = 0; t < periods(s); ++t) {
                for (const uint32_t look : lookaheads(s)) {
                  for (const auto& e : s.executions) {
                    for (const auto& k : switching_axis(s, e)) {
                      for (std::size_t r = 0; r < s.repeats; ++r) {
                        auto key = std::to_string(i) + "-" + instance_stem(s, i) + "-n" +
                                   std::to_string(n) + "-" + stem(robot) + "-" + stem(qos);
                        if (s.plans.size() > 1) key += "-" + s.plans[p].name;
                        if (s.uncertainty.size() > 1) key += "-u" + std::to_string(u);
                        if (periods(s) > 1) key += "-p" + std::to_string(t);
                        if (look != 0) key += "-l" + std::to_string(look);
                        key += knobs_key(e, k) + "-r" + std::to_string(r);
                        cells.push_back({i, n, p, robot, qos, u, r, t, key, e, k.commit, k.chain,
                                         look, k.margin_s, k.horizon, k.reach, k.window});
                      }
                    }
                  }
                }
              }
            }
          }
        }
      }
    }
  }
  return cells;
}

std::vector<std::string> execution_flags(const Cell& c) {
  std::vector<std::string> flags{"--execution", c.execution};
  if (c.commit_actions != 0) {
    flags.insert(flags.end(), {"--switch-commit-actions", std::to_string(c.commit_actions)});
  }
  if (c.chain_locations != 0) {
    flags.insert(flags.end(), {"--switch-chain-locations", std::to_string(c.chain_locations)});
  }
  if (c.margin_s) flags.insert(flags.end(), {"--switch-margin-s", json(*c.margin_s).dump()});
  if (c.horizon_actions != 0) {
    flags.insert(flags.end(), {"--switch-horizon-actions", std::to_string(c.horizon_actions)});
  }
  if (c.switch_lookahead_actions != 0) {
    flags.insert(flags.end(),
                 {"--switch-lookahead-actions", std::to_string(c.switch_lookahead_actions)});
  }
  if (c.window_pairs) {
    flags.insert(flags.end(), {"--switch-window-pairs", std::to_string(*c.window_pairs)});
  }
  return flags;
}

std::vector<std::string> output_flags(const Spec& s) {
  if (!s.state_rate_hz) return {};
  return {"--state-rate-hz", json(*s.state_rate_hz).dump()};
}

std::vector<std::string> uncertainty_flags(const Spec& s, const Cell& c) {
  std::vector<std::string> flags;
  for (const auto& [key, v] : s.uncertainty.at(c.uncertainty).items()) {
    std::string flag = "--" + key;
    std::replace(flag.begin(), flag.end(), '_', '-');
    flags.insert(flags.end(), {flag, v.dump()});
  }
  flags.insert(flags.end(), {"--seed", std::to_string(c.repeat)});
  return flags;
}

bool ran_to_its_end(const json& summary) {
  if (!summary.is_object()) return false;
  const auto outcome = summary.find(results::summary_key::kOutcome);
  return outcome == summary.end() || !outcome->is_string() ||
         *outcome != results::summary_key::kOutcomeStopped;
}

json result_row(const Spec& s, const Cell& c, const json& summary,
                std::optional<double> planner_runtime_s) {
  json row = {{"cell", c.key},
              {"map", stem(s.instances[c.instance].first)},
              {"scen", stem(s.instances[c.instance].second)},
              {"agents", c.agents},
              {"robot", stem(c.robot)},
              {"qos", stem(c.qos)},
              {"uncertainty", s.uncertainty.at(c.uncertainty).dump()},
              {"repeat", c.repeat},
              {"plan", s.plans.at(c.plan).name},
              {"axis", s.plans.at(c.plan).axis},
              {"clock", s.clock},
              {"execution", c.execution}};
  if (c.commit_actions != 0) row["switch_commit_actions"] = c.commit_actions;
  if (c.chain_locations != 0) row["switch_chain_locations"] = c.chain_locations;
  if (c.margin_s) row["switch_margin_s"] = *c.margin_s;
  if (c.horizon_actions != 0) row["switch_horizon_actions"] = c.horizon_actions;
  if (c.switch_lookahead_actions != 0) {
    row["switch_lookahead_actions"] = c.switch_lookahead_actions;
  }
  if (c.window_pairs) row["switch_window_pairs"] = *c.window_pairs;
  if (planner_runtime_s) row["planner_runtime_s"] = *planner_runtime_s;
  if (s.lifelong) {
    row["replan_period_s"] = s.lifelong->replan_period_s.at(c.period);
    if (c.lookahead != 0) row["lookahead"] = c.lookahead;
    row.erase("axis");
    // A LoRR problem brings its team: its size is summary.json's robots.
    if (c.agents == 0) row["agents"] = summary.value("robots", json(nullptr));
  }
  json fields = json::object();
  flatten(summary, "", fields);
  for (const auto& [k, v] : fields.items()) {
    if (!row.contains(k)) row[k] = v;
  }
  return row;
}

std::string results_csv(const std::vector<json>& rows) {
  // The parameters some row has: a lifelong run has no axis and no planner_runtime_s, a plan run
  // no replan_period_s (but a plan run's planner_runtime_s column stays, empty for plan files).
  const auto any_has = [&rows](const std::string& p) {
    return std::any_of(rows.begin(), rows.end(), [&](const json& r) { return r.contains(p); });
  };
  std::vector<std::string> columns;
  std::set<std::string> rest;
  for (const auto& p : kParams) {
    if (any_has(p) || (p == "planner_runtime_s" && any_has("axis"))) columns.push_back(p);
  }
  for (const auto& r : rows) {
    for (const auto& [k, v] : r.items()) {
      if (std::find(kParams.begin(), kParams.end(), k) == kParams.end()) rest.insert(k);
    }
  }
  columns.insert(columns.end(), rest.begin(), rest.end());
  std::string out;
  for (std::size_t i = 0; i < columns.size(); ++i) out += (i ? "," : "") + columns[i];
  out += "\n";
  for (const auto& r : rows) {
    for (std::size_t i = 0; i < columns.size(); ++i) {
      out += (i ? "," : "") + (r.contains(columns[i]) ? csv_field(r[columns[i]]) : "");
    }
    out += "\n";
  }
  return out;
}

}  // namespace smart::experiment
