#include "smart/grid/lorr.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <queue>
#include <type_traits>

#include "smart/grid/text.hpp"
#include "smart/grid/text_file.hpp"

namespace smart::grid {

namespace {

using nlohmann::json;

// Line of a byte offset, for JSON syntax errors.
int line_at(std::string_view text, std::size_t byte) {
  byte = std::min(byte, text.size());
  return 1 +
         static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(byte), '\n'));
}

json parse_json(std::string_view text, const std::string& source) {
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    throw InputError({{source, line_at(text, e.byte), -1,
                       std::string("not valid JSON (") + e.what() +
                           "); a LoRR problem is one JSON object, see Input_Output_Format.md"}});
  } catch (const json::exception& e) {  // e.g. a number too large for any JSON number type
    throw InputError({{source, 0, -1,
                       std::string("cannot be read as JSON (") + e.what() +
                           "); give numbers a 64-bit integer or a double can hold"}});
  }
}

// Whether `v` converts to T exactly: nlohmann's get<integer> of a double, or of a whole number
// out of T's range, is a plain cast, undefined behaviour past the range (libFuzzer, fuzz_lorr:
// a delayConfig "seed" of 7.8e24). A double with a whole value in range (3.0) is taken.
template <typename T>
bool converts_exactly(const json& v) {
  if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
    using L = std::numeric_limits<T>;
    if (v.is_number_unsigned()) return v.get<uint64_t>() <= static_cast<uint64_t>(L::max());
    if (v.is_number_integer()) {
      const auto x = v.get<int64_t>();
      if constexpr (L::is_signed) {
        return x >= static_cast<int64_t>(L::min()) && x <= static_cast<int64_t>(L::max());
      } else {
        return x >= 0 && static_cast<uint64_t>(x) <= static_cast<uint64_t>(L::max());
      }
    }
    if (v.is_number_float()) {
      const double d = v.get<double>(), bound = std::ldexp(1.0, L::digits);  // exact: 2^digits
      return std::isfinite(d) && d == std::trunc(d) && d < bound &&
             d >= (L::is_signed ? -bound : 0);
    }
  }
  return true;  // other kinds: get<T> throws for a wrong kind
}

// A required or optional field of a given JSON kind; problems go to `problems`.
template <typename T>
bool field(const json& j, const char* key, T& out, bool required, const std::string& source,
           const char* what, std::vector<Problem>& problems) {
  const auto it = j.find(key);
  if (it == j.end()) {
    if (required) {
      problems.push_back({source, 0, -1, std::string("missing \"") + key + "\" (" + what + ")"});
    }
    return false;
  }
  try {
    if (converts_exactly<T>(*it)) {
      out = it->get<T>();
      return true;
    }
  } catch (const json::exception&) {
  }
  problems.push_back(
      {source, 0, -1,
       std::string("\"") + key + "\" is " + excerpt(it->dump()) + "; it must be " + what});
  return false;
}

LorrDelayConfig parse_delay(const json& d, const std::string& source,
                            std::vector<Problem>& problems) {
  LorrDelayConfig c;
  c.present = true;
  const auto n = problems.size();
  field(d, "seed", c.seed, false, source, "a whole number", problems);
  field(d, "minDelay", c.min_delay_ticks, true, source, "ticks, a whole number", problems);
  field(d, "maxDelay", c.max_delay_ticks, true, source, "ticks, a whole number", problems);
  field(d, "eventModel", c.event_model, false, source, R"("bernoulli" or "poisson")", problems);
  field(d, "pDelay", c.p_delay, true, source, "a probability per tick", problems);
  field(d, "durationModel", c.duration_model, false, source, R"("uniform" or "gaussian")",
        problems);
  field(d, "gaussMeanRatio", c.gauss_mean_ratio, false, source, "a number", problems);
  field(d, "gaussStdRatio", c.gauss_std_ratio, false, source, "a number", problems);
  if (problems.size() != n) return c;
  auto bad = [&](const std::string& msg) {
    problems.push_back({source, 0, -1, "delayConfig: " + msg});
  };
  if (c.min_delay_ticks < 0 || c.max_delay_ticks < c.min_delay_ticks) {
    bad("minDelay " + std::to_string(c.min_delay_ticks) + " and maxDelay " +
        std::to_string(c.max_delay_ticks) + " must satisfy 0 <= minDelay <= maxDelay");
  }
  if (c.event_model != "bernoulli" && c.event_model != "poisson") {
    bad("eventModel \"" + c.event_model + R"(" is unknown; use "bernoulli" or "poisson")");
  }
  if (c.duration_model != "uniform" && c.duration_model != "gaussian") {
    bad("durationModel \"" + c.duration_model + R"(" is unknown; use "uniform" or "gaussian")");
  }
  if (!(c.p_delay >= 0 && c.p_delay <= 1)) bad("pDelay must be a probability in [0, 1]");
  if (c.gauss_std_ratio < 0) bad("gaussStdRatio must not be negative");
  return c;
}

// One number per non-comment line after the count line; `what` names the lines.
struct CountedLines {
  long long count = -1;
  int count_line = 0;
  std::vector<std::pair<int, std::string_view>> lines;  // line number, text
};

CountedLines counted_lines(std::string_view text, const std::string& source, const char* what,
                           std::vector<Problem>& problems) {
  CountedLines out;
  const auto lines = split_lines(text);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto t = trim(lines[i]);
    const int ln = static_cast<int>(i) + 1;
    if (t.empty() || t.starts_with('#')) continue;
    if (out.count >= 0) {
      out.lines.emplace_back(ln, t);
      continue;
    }
    const auto n = parse_int(t);
    if (!n || *n < 0 || *n > kMaxRobots) {
      problems.push_back({source, ln, -1,
                          "expected the number of " + std::string(what) + ", found '" + excerpt(t) +
                              "'; the first line after the '#' comment is a count"});
      return out;
    }
    out.count = *n;
    out.count_line = ln;
  }
  if (out.count < 0) problems.push_back({source, 0, -1, std::string("no ") + what + " count"});
  return out;
}

// A linear cell id `row * width + col` that must be a free cell of `grid`.
std::optional<Cell> cell_of_id(std::string_view token, const Grid& grid, std::string& error) {
  const auto id = parse_int(trim(token));
  const long long cells = static_cast<long long>(grid.width()) * grid.height();
  if (!id || *id < 0 || *id >= cells) {
    error = "cell id '" + excerpt(trim(token)) + "' is not in 0.." + std::to_string(cells - 1) +
            " (row * width + col on the " + std::to_string(grid.width()) + "x" +
            std::to_string(grid.height()) + " map)";
    return std::nullopt;
  }
  const Cell c{static_cast<int32_t>(*id % grid.width()), static_cast<int32_t>(*id / grid.width())};
  if (grid.blocked(c)) {
    error = "cell " + to_string_cell_id(grid, c) + " is an obstacle; choose a free cell";
    return std::nullopt;
  }
  return c;
}

void check_count(const CountedLines& c, const std::string& source, const char* what,
                 std::vector<Problem>& problems) {
  if (c.count >= 0 && static_cast<std::size_t>(c.count) != c.lines.size()) {
    problems.push_back({source, c.count_line, -1,
                        "the count says " + std::to_string(c.count) + " " + what + " but " +
                            std::to_string(c.lines.size()) +
                            " lines follow; fix the count or the lines"});
  }
}

}  // namespace

std::string to_string_cell_id(const Grid& grid, Cell c) {
  return std::to_string(static_cast<long long>(c.y) * grid.width() + c.x) + " " + to_string(c);
}

LorrSpec parse_lorr_spec(std::string_view text, const std::string& source) {
  const json j = parse_json(text, source);
  std::vector<Problem> problems;
  if (!j.is_object()) throw InputError({{source, 1, -1, "a LoRR problem is a JSON object"}});
  LorrSpec s;
  field(j, "mapFile", s.map_file, true, source, "the map's path, a string", problems);
  field(j, "agentFile", s.agent_file, true, source, "the agents file's path, a string", problems);
  field(j, "taskFile", s.task_file, true, source, "the tasks file's path, a string", problems);
  long long team = 0;
  if (field(j, "teamSize", team, true, source, "the number of robots", problems) &&
      (team <= 0 || team > kMaxRobots)) {
    problems.push_back(
        {source, 0, -1,
         "teamSize " + std::to_string(team) + " must be 1.." + std::to_string(kMaxRobots)});
  }
  s.team_size = static_cast<std::size_t>(std::max(0LL, team));
  if (field(j, "numTasksReveal", s.num_tasks_reveal, false, source, "a number", problems) &&
      !(s.num_tasks_reveal > 0 && s.num_tasks_reveal <= 1000)) {
    problems.push_back({source, 0, -1, "numTasksReveal must be a number in (0, 1000]"});
  }
  std::string version;
  field(j, "version", version, false, source, "a string such as \"2026 LoRR\"", problems);
  const bool v2026 = version.find("2026") != std::string::npos || j.contains("agentCounter") ||
                     j.contains("delayConfig");
  s.version = v2026 ? 2026 : 2024;
  if (field(j, "agentCounter", s.agent_counter, false, source, "ticks per action", problems) &&
      (s.agent_counter < 1 || s.agent_counter > 1000)) {
    problems.push_back({source, 0, -1, "agentCounter must be 1..1000 ticks per action"});
  }
  if (field(j, "agentSize", s.agent_size, false, source, "cells", problems) &&
      !(s.agent_size >= 0 && s.agent_size <= 1)) {
    problems.push_back({source, 0, -1, "agentSize must be in [0, 1] cells"});
  }
  if (const auto d = j.find("delayConfig"); d != j.end()) {
    if (d->is_object()) {
      s.delay = parse_delay(*d, source, problems);
    } else {
      problems.push_back({source, 0, -1, "\"delayConfig\" must be an object"});
    }
  }
  throw_if_any(problems);
  return s;
}

std::vector<Cell> parse_lorr_agents(std::string_view text, const std::string& source,
                                    const Grid& grid, std::size_t expect) {
  std::vector<Problem> problems;
  const auto c = counted_lines(text, source, "agents", problems);
  check_count(c, source, "agents", problems);
  if (expect > 0 && c.lines.size() < expect) {
    problems.push_back({source, 0, -1,
                        "teamSize is " + std::to_string(expect) + " but the file has only " +
                            std::to_string(c.lines.size()) +
                            " agents; add starts or lower teamSize"});
  }
  std::vector<Cell> starts;
  std::vector<int32_t> taken(static_cast<std::size_t>(grid.width()) * grid.height(), -1);
  for (const auto& [ln, t] : c.lines) {
    if (expect > 0 && starts.size() >= expect) break;
    const int robot = static_cast<int>(starts.size());
    std::string error;
    const auto cell = cell_of_id(t, grid, error);
    if (!cell) {
      problems.push_back({source, ln, robot, "start " + error});
      starts.push_back({});
      continue;
    }
    if (auto& owner = taken[grid.index(*cell)]; owner >= 0) {
      problems.push_back({source, ln, robot,
                          "starts on " + to_string_cell_id(grid, *cell) + " like robot " +
                              std::to_string(owner) + "; every robot needs its own start"});
    } else {
      owner = robot;
    }
    starts.push_back(*cell);
  }
  throw_if_any(problems);
  return starts;
}

std::vector<Task> parse_lorr_tasks(std::string_view text, const std::string& source,
                                   const Grid& grid) {
  std::vector<Problem> problems;
  const auto c = counted_lines(text, source, "tasks", problems);
  check_count(c, source, "tasks", problems);
  std::vector<Task> tasks;
  tasks.reserve(c.lines.size());
  for (const auto& [ln, t] : c.lines) {
    Task task{static_cast<uint32_t>(tasks.size()), ln, {}};
    for (const auto token : split(t, ',')) {
      std::string error;
      const auto cell = cell_of_id(token, grid, error);
      if (cell) {
        task.errands.push_back(*cell);
      } else {
        problems.push_back({source, ln, -1,
                            "task " + std::to_string(task.id) + " errand " +
                                std::to_string(task.errands.size() + 1) + ": " + error});
      }
    }
    tasks.push_back(std::move(task));
  }
  if (problems.empty() && tasks.empty()) {
    problems.push_back({source, 0, -1, "no tasks; a lifelong run needs at least one"});
  }
  throw_if_any(problems);
  return tasks;
}

Grid parse_lsmart_map(std::string_view text, const std::string& source, MapMarks* marks) {
  const json j = parse_json(text, source);
  std::vector<Problem> problems;
  long long rows = 0, cols = 0;
  std::vector<std::string> layout;
  field(j, "n_row", rows, true, source, "the number of rows", problems);
  field(j, "n_col", cols, true, source, "the number of columns", problems);
  field(j, "layout", layout, true, source, "a list of row strings", problems);
  throw_if_any(problems);
  if (rows <= 0 || cols <= 0 || rows > kMaxGridSide || cols > kMaxGridSide ||
      static_cast<long long>(layout.size()) != rows) {
    throw InputError({{source, 0, -1,
                       "n_row " + std::to_string(rows) + " and n_col " + std::to_string(cols) +
                           " must be positive and n_row must equal the layout's " +
                           std::to_string(layout.size()) + " rows"}});
  }
  std::vector<uint8_t> blocked(static_cast<std::size_t>(rows * cols), 1);
  for (int32_t y = 0; y < rows; ++y) {
    const auto& row = layout[static_cast<std::size_t>(y)];
    if (static_cast<long long>(row.size()) != cols) {
      problems.push_back({source, 0, -1,
                          "layout row " + std::to_string(y) + " has " + std::to_string(row.size()) +
                              " symbols, not n_col " + std::to_string(cols)});
      continue;
    }
    for (int32_t x = 0; x < cols; ++x) {
      const char s = row[static_cast<std::size_t>(x)];
      if (s != '.' && s != '@' && s != 'T' && s != 'w' && s != 'e') {
        problems.push_back({source, 0, -1,
                            "layout row " + std::to_string(y) + " column " + std::to_string(x) +
                                ": unknown symbol '" + std::string(1, s) +
                                "'; use '.', 'w', 'e' (free) or '@', 'T' (blocked)"});
        continue;
      }
      blocked[static_cast<std::size_t>(y * cols + x)] = s == '@' || s == 'T';
      if (marks && s == 'w') marks->workstations.push_back({x, y});
      if (marks && s == 'e') marks->endpoints.push_back({x, y});
    }
  }
  throw_if_any(problems);
  return Grid(static_cast<int32_t>(cols), static_cast<int32_t>(rows), std::move(blocked), source);
}

std::vector<Problem> check_tasks_reachable(const Grid& grid, const std::vector<Cell>& starts,
                                           const std::vector<Task>& tasks,
                                           const std::string& source) {
  // Flood fill from every start: the cells some robot can reach.
  std::vector<uint8_t> reach(static_cast<std::size_t>(grid.width()) * grid.height(), 0);
  std::queue<Cell> open;
  for (const Cell s : starts) {
    if (grid.free(s) && !reach[grid.index(s)]) reach[grid.index(s)] = 1, open.push(s);
  }
  while (!open.empty()) {
    const Cell c = open.front();
    open.pop();
    for (const Cell n :
         {Cell{c.x + 1, c.y}, Cell{c.x - 1, c.y}, Cell{c.x, c.y + 1}, Cell{c.x, c.y - 1}}) {
      if (grid.free(n) && !reach[grid.index(n)]) reach[grid.index(n)] = 1, open.push(n);
    }
  }
  std::vector<Problem> problems;
  for (const auto& t : tasks) {
    for (std::size_t k = 0; k < t.errands.size(); ++k) {
      if (reach[grid.index(t.errands[k])]) continue;
      problems.push_back({source, t.line, -1,
                          "task " + std::to_string(t.id) + " errand " + std::to_string(k + 1) +
                              " at " + to_string_cell_id(grid, t.errands[k]) +
                              " is walled off from every robot's start; move it or drop the task"});
      break;
    }
  }
  return problems;
}

Grid load_task_map(const std::filesystem::path& path, MapMarks* marks) {
  const std::string text = read_text_file(path, "map");
  if (path.extension() == ".json") return parse_lsmart_map(text, path.string(), marks);
  return parse_map(text, path.string(), MapDialect::kLorr, marks);
}

LorrProblem load_lorr_problem(const std::filesystem::path& problem_json) {
  LorrProblem p;
  p.source = problem_json.string();
  p.spec = parse_lorr_spec(read_text_file(problem_json, "LoRR problem"), p.source);
  const auto dir = problem_json.parent_path();
  p.grid = load_task_map(dir / p.spec.map_file, &p.marks);
  const auto agents = dir / p.spec.agent_file;
  p.starts = parse_lorr_agents(read_text_file(agents, "LoRR agents"), agents.string(), p.grid,
                               p.spec.team_size);
  const auto tasks = dir / p.spec.task_file;
  p.tasks = parse_lorr_tasks(read_text_file(tasks, "LoRR tasks"), tasks.string(), p.grid);
  throw_if_any(check_tasks_reachable(p.grid, p.starts, p.tasks, tasks.string()));
  return p;
}

}  // namespace smart::grid
