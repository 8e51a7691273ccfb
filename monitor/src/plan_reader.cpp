#include "smart/monitor/plan_reader.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "smart/monitor/vocabulary.hpp"

namespace smart::monitor {

namespace {

Cell make_cell(long long a, long long b, AxisOrder axis) {
  return axis == AxisOrder::kXY ? Cell{static_cast<int32_t>(a), static_cast<int32_t>(b)}
                                : Cell{static_cast<int32_t>(b), static_cast<int32_t>(a)};
}

// A tiny cursor over one line.
struct Cursor {
  std::string_view s;
  std::size_t i = 0;
  void skip_spaces() {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
  }
  bool eat(char c) {
    skip_spaces();
    if (i < s.size() && s[i] == c) {
      ++i;
      return true;
    }
    return false;
  }
  bool eat(std::string_view word) {
    skip_spaces();
    if (s.substr(i).starts_with(word)) {
      i += word.size();
      return true;
    }
    return false;
  }
  bool at_end() {
    skip_spaces();
    return i >= s.size();
  }
  std::optional<long long> integer() {
    skip_spaces();
    long long v = 0;
    const auto [p, ec] = std::from_chars(s.data() + i, s.data() + s.size(), v);
    if (ec != std::errc()) return std::nullopt;
    i = static_cast<std::size_t>(p - s.data());
    return v;
  }
  // Text up to (not including) `c`, consuming `c`; nullopt when `c` is missing.
  std::optional<std::string_view> until(char c) {
    const auto p = s.find(c, i);
    if (p == std::string_view::npos) return std::nullopt;
    auto out = s.substr(i, p - i);
    i = p + 1;
    return out;
  }
};

// Parses "a,b" or "a,b,t" (the inside of parentheses).
struct Tuple {
  long long a = 0, b = 0;
  std::optional<double> t;
};
std::optional<Tuple> parse_tuple(std::string_view inside, std::string* error) {
  const auto parts = split(inside, ',');
  if (parts.size() != 2 && parts.size() != 3) {
    *error = "'(" + excerpt(inside) + ")' must hold 2 numbers (a,b) or 3 (a,b,t)";
    return std::nullopt;
  }
  const auto a = parse_int(parts[0]), b = parse_int(parts[1]);
  if (!a || !b) {
    *error = "'(" + excerpt(inside) + ")': cell coordinates must be whole numbers";
    return std::nullopt;
  }
  if (std::abs(*a) > grid::kMaxGridSide || std::abs(*b) > grid::kMaxGridSide) {
    *error = "'(" + excerpt(inside) + ")': cell coordinates must be between -" +
             std::to_string(grid::kMaxGridSide) + " and " + std::to_string(grid::kMaxGridSide);
    return std::nullopt;
  }
  Tuple t{*a, *b, std::nullopt};
  if (parts.size() == 3) {
    t.t = parse_double(parts[2]);
    if (!t.t) {
      *error = "'(" + excerpt(inside) + ")': time must be a number";
      return std::nullopt;
    }
  }
  return t;
}

// What is wrong with one YAML step {x, y, t} beyond its types: repeated keys (yaml-cpp keeps
// one silently), coordinates that would wrap, times that are not finite.
std::string yaml_step_problem(const YAML::Node& step) {
  if (!step.IsMap()) return "each step must be a mapping {x, y, t}";
  std::set<std::string> keys;
  for (const auto& kv : step) {
    const auto key = kv.first.as<std::string>();
    if (!keys.insert(key).second) return "key '" + excerpt(key) + "' appears twice in one step";
  }
  for (const char* k : {"x", "y"}) {
    if (step[k] && std::abs(step[k].as<long long>()) > grid::kMaxGridSide) {
      return std::string(k) + " must be between -" + std::to_string(grid::kMaxGridSide) + " and " +
             std::to_string(grid::kMaxGridSide);
    }
  }
  if (step["t"] && !std::isfinite(step["t"].as<double>())) return "t must be a finite number";
  return {};
}

// Collects paths by robot id and reports duplicates, gaps and empty paths.
class PathCollector {
 public:
  PathCollector(const std::string& source, std::vector<Problem>& problems)
      : source_(source), problems_(problems) {}
  RobotPath* add(int robot, int line) {
    auto [it, fresh] = paths_.emplace(robot, RobotPath{robot, line, {}});
    if (!fresh) {
      problems_.push_back({source_, line, robot,
                           "robot " + std::to_string(robot) + " appears twice (first on line " +
                               std::to_string(it->second.line) + "); keep one path per robot"});
      return nullptr;
    }
    return &it->second;
  }
  std::vector<RobotPath> finish() {
    std::vector<RobotPath> out;
    int expected = 0;
    for (auto& [robot, path] : paths_) {
      if (robot != expected) {
        problems_.push_back(
            {source_, path.line, robot,
             "robots must be numbered 0..N-1, but robot " + std::to_string(expected) +
                 (robot - expected > 1 ? " to " + std::to_string(robot - 1) + " are missing"
                                       : " is missing")});
        expected = robot;
      }
      // An empty path is only worth saying when no parse problem explains it already.
      const int id = robot;  // a structured binding cannot be captured before C++20 (clang 14)
      const bool explained = std::any_of(problems_.begin(), problems_.end(),
                                         [id](const Problem& p) { return p.robot == id; });
      if (path.steps.empty() && !explained) {
        problems_.push_back({source_, path.line, robot, "path has no steps"});
      }
      ++expected;
      out.push_back(std::move(path));
    }
    if (out.empty() && problems_.empty()) {
      problems_.push_back({source_, 0, -1, "the plan contains no robot paths"});
    }
    return out;
  }

 private:
  const std::string& source_;
  std::vector<Problem>& problems_;
  std::map<int, RobotPath> paths_;
};

void parse_smart(std::string_view text, Plan& plan, AxisOrder axis,
                 std::vector<Problem>& problems) {
  PathCollector collector(plan.source, problems);
  const auto lines = split_lines(text);
  int tuple_size = 0;  // 2 or 3, fixed by the first step in the file
  for (std::size_t li = 0; li < lines.size(); ++li) {
    const int ln = static_cast<int>(li) + 1;
    Cursor c{lines[li]};
    if (c.at_end() || trim(lines[li]).starts_with("#")) continue;  // a comment (`# axis: xy`)
    if (!c.eat("Agent")) {
      problems.push_back({plan.source, ln, -1,
                          "expected 'Agent <i>:(...)->...', found '" + excerpt(lines[li]) + "'"});
      continue;
    }
    const auto id = c.integer();
    if (!id || *id < 0 || *id > grid::kMaxRobots || !c.eat(':')) {
      problems.push_back(
          {plan.source, ln, -1,
           "expected a robot number and ':' after 'Agent', found '" + excerpt(lines[li]) + "'"});
      continue;
    }
    const int robot = static_cast<int>(*id);
    RobotPath* path = collector.add(robot, ln);
    RobotPath scratch;
    if (path == nullptr) path = &scratch;
    while (!c.at_end()) {
      if (!c.eat('(')) {
        problems.push_back({plan.source, ln, robot,
                            "step " + std::to_string(path->steps.size()) +
                                ": expected '(' at column " + std::to_string(c.i + 1) +
                                "; the line may be truncated or malformed"});
        break;
      }
      const auto inside = c.until(')');
      if (!inside) {
        problems.push_back({plan.source, ln, robot,
                            "step " + std::to_string(path->steps.size()) +
                                ": missing ')'; the line may be truncated"});
        break;
      }
      std::string error;
      const auto t = parse_tuple(*inside, &error);
      if (!t) {
        problems.push_back(
            {plan.source, ln, robot, "step " + std::to_string(path->steps.size()) + ": " + error});
        break;
      }
      const int size = t->t ? 3 : 2;
      if (tuple_size == 0) tuple_size = size;
      if (size != tuple_size) {
        problems.push_back({plan.source, ln, robot,
                            "step " + std::to_string(path->steps.size()) + " has " +
                                std::to_string(size) + " numbers but earlier steps have " +
                                std::to_string(tuple_size) +
                                "; use (a,b,t) everywhere or (a,b) everywhere"});
        break;
      }
      const double time = t->t ? *t->t : static_cast<double>(path->steps.size());
      path->steps.push_back({make_cell(t->a, t->b, axis), time, ln});
      if (!c.eat("->") && !c.at_end()) {
        problems.push_back({plan.source, ln, robot,
                            "expected '->' between steps at column " + std::to_string(c.i + 1)});
        break;
      }
    }
  }
  plan.timed = tuple_size == 3;
  plan.paths = collector.finish();
}

void parse_lacam(std::string_view text, Plan& plan, AxisOrder axis,
                 std::vector<Problem>& problems) {
  const auto lines = split_lines(text);
  std::size_t li = 0;
  const bool has_solution_marker = text.find("solution=") != std::string_view::npos;
  if (has_solution_marker) {
    while (li < lines.size() && !trim(lines[li]).starts_with("solution=")) ++li;
    ++li;
  }
  std::vector<RobotPath> paths;
  long long expected_t = 0;
  for (; li < lines.size(); ++li) {
    const int ln = static_cast<int>(li) + 1;
    Cursor c{lines[li]};
    if (c.at_end()) continue;
    const auto t = c.integer();
    if (!t || !c.eat(':')) {
      problems.push_back(
          {plan.source, ln, -1,
           "expected '<timestep>:(x,y),(x,y),...', found '" + excerpt(lines[li]) + "'"});
      continue;
    }
    if (*t != expected_t) {
      problems.push_back({plan.source, ln, -1,
                          "timestep " + std::to_string(*t) + " follows timestep " +
                              std::to_string(expected_t - 1) + "; timesteps must be consecutive"});
    }
    expected_t = *t + 1;
    std::size_t robot = 0;
    while (!c.at_end()) {
      if (!c.eat('(')) {
        problems.push_back({plan.source, ln, static_cast<int>(robot),
                            "expected '(' at column " + std::to_string(c.i + 1)});
        break;
      }
      const auto inside = c.until(')');
      std::string error;
      const auto tup = inside ? parse_tuple(*inside, &error) : std::nullopt;
      if (!tup || tup->t) {
        problems.push_back({plan.source, ln, static_cast<int>(robot),
                            inside ? (tup ? "positions take 2 numbers (x,y)" : error)
                                   : "missing ')'; the line may be truncated"});
        break;
      }
      if (robot >= paths.size()) {
        if (*t != 0) {
          problems.push_back({plan.source, ln, static_cast<int>(robot),
                              "timestep " + std::to_string(*t) +
                                  " lists more robots than "
                                  "timestep 0 (" +
                                  std::to_string(paths.size()) + ")"});
          break;
        }
        paths.push_back(RobotPath{static_cast<int>(robot), ln, {}});
      }
      paths[robot].steps.push_back({make_cell(tup->a, tup->b, axis), static_cast<double>(*t), ln});
      ++robot;
      c.eat(',');
    }
    if (*t != 0 && robot < paths.size()) {
      problems.push_back({plan.source, ln, static_cast<int>(robot),
                          "timestep " + std::to_string(*t) + " lists " + std::to_string(robot) +
                              " robots but timestep 0 lists " + std::to_string(paths.size())});
    }
  }
  if (paths.empty() && problems.empty()) {
    problems.push_back(
        {plan.source, 0, -1, "no 'solution=' timesteps found; is the plan unsolved (solved=0)?"});
  }
  plan.timed = false;
  plan.paths = std::move(paths);
}

void parse_yaml(std::string_view text, Plan& plan, AxisOrder axis, std::vector<Problem>& problems) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::ParserException& e) {
    problems.push_back({plan.source, e.mark.line + 1, -1, "YAML syntax error: " + e.msg});
    return;
  }
  const auto schedule = root.IsMap() ? root["schedule"] : YAML::Node();
  if (!schedule || !schedule.IsMap()) {
    problems.push_back({plan.source, 0, -1,
                        "no 'schedule:' mapping of agent names to paths (libMultiRobotPlanning "
                        "output format)"});
    return;
  }
  PathCollector collector(plan.source, problems);
  int order = 0;
  for (const auto& kv : schedule) {
    const int ln = kv.first.Mark().line + 1;
    if (!kv.first.IsScalar()) {  // found by fuzzing: "[a]: ..." escaped as BadConversion
      problems.push_back({plan.source, ln, -1, "an agent name must be a plain word, e.g. agent3"});
      continue;
    }
    const auto name = kv.first.Scalar();
    // "agent7" is robot 7; names without a number are numbered in file order.
    std::size_t d = name.size();
    while (d > 0 && std::isdigit(static_cast<unsigned char>(name[d - 1]))) --d;
    const auto suffix = parse_int(std::string_view(name).substr(d));
    if (suffix && *suffix > grid::kMaxRobots) {
      problems.push_back({plan.source, ln, -1,
                          "'" + excerpt(name) + "': robot number too large (at most " +
                              std::to_string(grid::kMaxRobots) + ")"});
      continue;
    }
    const int robot = suffix ? static_cast<int>(*suffix) : order;
    ++order;
    RobotPath* path = collector.add(robot, ln);
    if (path == nullptr) continue;
    if (!kv.second.IsSequence()) {
      problems.push_back({plan.source, ln, robot, "'" + name + "' must be a list of {x, y, t}"});
      continue;
    }
    for (const auto& step : kv.second) {
      const int sl = step.Mark().line + 1;
      try {
        if (auto why = yaml_step_problem(step); !why.empty()) {
          problems.push_back({plan.source, sl, robot, why});
          break;
        }
        const auto x = step["x"].as<long long>(), y = step["y"].as<long long>();
        const auto t = step["t"].as<double>();
        path->steps.push_back({make_cell(x, y, axis), t, sl});
      } catch (const YAML::Exception&) {
        problems.push_back({plan.source, sl, robot,
                            "each step needs whole numbers x, y and a number t, e.g. "
                            "'- {x: 3, y: 4, t: 2}'"});
        break;
      }
    }
  }
  plan.timed = true;
  plan.paths = collector.finish();
}

}  // namespace

AxisOrder parse_axis_order(const std::string& s) {
  if (s == "xy") return AxisOrder::kXY;
  if (s == "rowcol" || s == "yx") return AxisOrder::kRowCol;
  throw std::invalid_argument("unknown axis order '" + s + "'; use xy or rowcol");
}

PlanFormat parse_plan_format(const std::string& s) {
  if (s == "auto") return PlanFormat::kAuto;
  if (s == "smart" || s == "lns2") return PlanFormat::kSmart;
  if (s == "lacam" || s == "pibt") return PlanFormat::kLacam;
  if (s == "yaml") return PlanFormat::kYaml;
  throw std::invalid_argument("unknown plan format '" + s + "'; use auto, smart, lacam or yaml");
}

// The axis a SMART-format file declares in a leading comment "# axis: xy" or "# axis: rowcol"
// (`smart plan` writes one), if any.
std::optional<AxisOrder> declared_axis(std::string_view text) {
  for (const auto raw : split_lines(text)) {
    const auto line = trim(raw);
    if (line.empty()) continue;
    if (!line.starts_with("#")) return std::nullopt;
    if (line == "# axis: xy") return AxisOrder::kXY;
    if (line == "# axis: rowcol") return AxisOrder::kRowCol;
  }
  return std::nullopt;
}

PlanFormat detect_plan_format(std::string_view text) {
  for (const auto raw : split_lines(text)) {
    const auto line = trim(raw);
    if (line.empty() || line.starts_with("#")) continue;
    if (line.starts_with("Agent")) return PlanFormat::kSmart;
    if (line.find('=') != std::string_view::npos) return PlanFormat::kLacam;  // key=value header
    if (!line.empty() && std::isdigit(static_cast<unsigned char>(line[0])) &&
        line.find(":(") != std::string_view::npos) {
      return PlanFormat::kLacam;
    }
    if (line.starts_with("schedule:") || line.starts_with("statistics:")) return PlanFormat::kYaml;
    return PlanFormat::kAuto;
  }
  return PlanFormat::kAuto;
}

Plan parse_plan(std::string_view text, const std::string& source, const PlanReadOptions& opt) {
  Plan plan;
  plan.source = source;
  plan.format = opt.format == PlanFormat::kAuto ? detect_plan_format(text) : opt.format;
  std::vector<Problem> problems;
  switch (plan.format) {
    case PlanFormat::kAuto: {
      const auto lines = split_lines(text);
      problems.push_back({source, 1, -1,
                          "cannot tell the plan format from '" +
                              excerpt(lines.empty() ? std::string_view{} : lines[0]) +
                              "'; pass --format smart, lacam or yaml"});
      break;
    }
    case PlanFormat::kSmart: {
      const auto declared = declared_axis(text);
      if (declared && opt.axis && *declared != *opt.axis) {
        problems.push_back({source, 1, -1,
                            "the file declares '# axis: " + to_string(*declared) + "' but --axis " +
                                to_string(*opt.axis) + " was given; drop --axis or fix the file"});
        break;
      }
      if (!opt.axis && !declared) {
        problems.push_back(
            {source, 0, -1,
             "SMART/MAPF-LNS2 path files do not say whether '(a,b)' is (x,y) or (row,col); pass "
             "--axis xy or --axis rowcol (SMART's example_paths_xy.txt is xy, MAPF-LNS2 "
             "--outputPaths and scen_1_*_paths.txt are rowcol)"});
        break;
      }
      plan.axis = opt.axis ? *opt.axis : *declared;
      parse_smart(text, plan, plan.axis, problems);
      break;
    }
    case PlanFormat::kLacam:
      plan.axis = opt.axis.value_or(AxisOrder::kXY);
      parse_lacam(text, plan, plan.axis, problems);
      break;
    case PlanFormat::kYaml:
      plan.axis = opt.axis.value_or(AxisOrder::kXY);
      parse_yaml(text, plan, plan.axis, problems);
      break;
  }
  throw_if_any(std::move(problems));
  return plan;
}

}  // namespace smart::monitor
