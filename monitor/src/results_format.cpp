#include "smart/monitor/results_format.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <type_traits>

namespace smart::results {

bool is_results_file(std::string_view name) {
  return std::find(kFiles.begin(), kFiles.end(), name) != kFiles.end();
}

std::string sim_report_name(uint32_t shard) { return "sim-" + std::to_string(shard) + ".json"; }

SimReport parse_sim_report(std::string_view text, const std::string& source) {
  std::string_view last;
  for (std::size_t at = 0; at < text.size();) {
    const auto end = std::min(text.find('\n', at), text.size());
    if (end > at) last = text.substr(at, end - at);
    at = end + 1;
  }
  const auto j = nlohmann::json::parse(last, nullptr, false);
  if (!j.is_object()) {
    throw std::invalid_argument(source +
                                ": no sim report (its last line is not a JSON object); "
                                "the sim host stopped before it could write one");
  }
  auto field = [&](const char* key, auto fallback, bool required) {
    using T = decltype(fallback);
    const auto it = j.find(key);
    if (it == j.end() && !required) return fallback;
    const bool fits = it != j.end() && (std::is_same_v<T, bool>          ? it->is_boolean()
                                        : std::is_same_v<T, std::string> ? it->is_string()
                                        : std::is_floating_point_v<T>    ? it->is_number()
                                                                      : it->is_number_unsigned());
    if (!fits) {
      throw std::invalid_argument(source + ": sim report key \"" + key +
                                  "\" is missing or of the wrong type");
    }
    return it->template get<T>();
  };
  using namespace sim_report_key;
  return {field(kOk, false, true),
          field(kError, std::string(), false),
          field(kSimTimeS, 0.0, true),
          field(kRobotContacts, uint64_t{0}, true),
          field(kWallContacts, uint64_t{0}, true),
          field(kHandoversIn, uint64_t{0}, false)};
}

namespace {

// One field as %.10g (doubles) or decimal (integers), then `sep`. std::to_chars with a format
// and a precision converts as printf does (C++17 [charconv.to.chars]), without the stream's
// locale and multi-precision path: a quarter of the monitor's CPU in a 1000-robot run (issue 15).
template <class T>
void put(std::string& out, T v, char sep = ',') {
  char buf[32];
  std::to_chars_result r;
  if constexpr (std::is_floating_point_v<T>) {
    r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 10);
  } else {
    r = std::to_chars(buf, buf + sizeof buf, v);
  }
  out.append(buf, r.ptr);
  if (sep) out.push_back(sep);
}

// An optional field: empty when not known.
template <class T>
void put(std::string& out, const std::optional<T>& v, char sep = ',') {
  if (v) put(out, *v, 0);
  if (sep) out.push_back(sep);
}

}  // namespace

double as_written(double v) {
  std::string text;
  put(text, v, 0);
  double back = v;
  std::from_chars(text.data(), text.data() + text.size(), back);
  return back;
}

namespace {

// Lines of `text` after the header, with their 1-based numbers; empty lines are skipped.
template <class F>
void rows_of(std::string_view text, F&& row) {
  std::size_t line_no = 0;
  while (!text.empty()) {
    const auto nl = std::min(text.find('\n'), text.size());
    std::string_view line = text.substr(0, nl);
    text.remove_prefix(std::min(nl + 1, text.size()));
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (++line_no == 1 || line.empty()) continue;
    row(line, line_no);
  }
}

// The next comma-separated field of `line` (consumed).
std::string_view next_field(std::string_view& line) {
  const auto comma = std::min(line.find(','), line.size());
  const auto f = line.substr(0, comma);
  line.remove_prefix(std::min(comma + 1, line.size()));
  return f;
}

template <class T>
bool number(std::string_view f, T& out) {
  const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), out);
  if (ec != std::errc() || end != f.data() + f.size()) return false;
  if constexpr (std::is_floating_point_v<T>) return std::isfinite(out);
  return true;
}

// An empty field is "not known"; anything else must be a number (finite: number()).
template <class T>
bool optional_number(std::string_view f, std::optional<T>& out) {
  out.reset();
  if (f.empty()) return true;
  T v = 0;
  if (!number(f, v)) return false;
  out = v;
  return true;
}

// "x y;x y" (at most kMaxTaskCells pairs; empty: none).
constexpr std::size_t kMaxTaskCells = 1024;
bool cells_of(std::string_view f, std::vector<std::pair<int32_t, int32_t>>& out) {
  out.clear();
  if (!f.empty() && f.back() == ';') return false;
  while (!f.empty()) {
    const auto semi = std::min(f.find(';'), f.size());
    auto pair = f.substr(0, semi);
    f.remove_prefix(std::min(semi + 1, f.size()));
    const auto space = pair.find(' ');
    std::pair<int32_t, int32_t> c;
    if (space == std::string_view::npos || !number(pair.substr(0, space), c.first) ||
        !number(pair.substr(space + 1), c.second) || out.size() >= kMaxTaskCells) {
      return false;
    }
    out.push_back(c);
  }
  return true;
}

std::invalid_argument bad_row(std::string_view file, std::size_t line, std::string_view expected) {
  return std::invalid_argument(std::string(file) + " line " + std::to_string(line) + ": expected " +
                               std::string(expected));
}

}  // namespace

void append_row(std::string& out, const RobotRow& r) {
  put(out, r.robot);
  put(out, r.finish_time_s);
  put(out, r.waiting_time_s);
  put(out, r.stops);
  put(out, r.actions);
  put(out, r.lower_bound_s, '\n');
}

std::vector<RobotRow> parse_robots_csv(std::string_view text) {
  std::vector<RobotRow> rows;
  rows_of(text, [&](std::string_view line, std::size_t line_no) {
    RobotRow r;
    const bool ok = number(next_field(line), r.robot) &&
                    optional_number(next_field(line), r.finish_time_s) &&
                    number(next_field(line), r.waiting_time_s) &&
                    number(next_field(line), r.stops) && number(next_field(line), r.actions) &&
                    optional_number(next_field(line), r.lower_bound_s) && line.empty();
    if (!ok) throw bad_row(kRobotsCsv, line_no, kRobotsHeader);
    rows.push_back(r);
  });
  return rows;
}

void append_row(std::string& out, const ActionRow& r) {
  put(out, r.robot);
  put(out, r.action);
  out.append(r.type == ActionType::kMove ? "move," : "rotate,");
  put(out, r.finish_time_s, '\n');
}

void for_each_action_row(std::string_view text,
                         const std::function<void(const ActionRow&, std::size_t line)>& row) {
  rows_of(text, [&](std::string_view line, std::size_t line_no) {
    ActionRow r;
    bool ok = number(next_field(line), r.robot) && number(next_field(line), r.action);
    const auto type = next_field(line);
    ok = ok && (type == "move" || type == "rotate") &&
         optional_number(next_field(line), r.finish_time_s) && line.empty() &&
         (!r.finish_time_s || *r.finish_time_s >= 0);
    if (!ok) throw bad_row(kActionsCsv, line_no, "robot,action,move|rotate,finish_time_s (>= 0)");
    r.type = type == "move" ? ActionType::kMove : ActionType::kRotate;
    row(r, line_no);
  });
}

void append_row(std::string& out, const StateRow& s) {
  put(out, s.t_s);
  put(out, s.robot);
  for (const double v : {s.x_m, s.y_m, s.yaw_rad, s.v_mps, s.w_radps, s.left_mps, s.right_mps}) {
    put(out, v);
  }
  put(out, s.queue, '\n');
}

std::optional<StateRow> parse_state_line(std::string_view line) {
  StateRow s;
  double robot = -1;
  if (!number(next_field(line), s.t_s) || !number(next_field(line), robot) || robot < 0 ||
      robot > 1e7 || !number(next_field(line), s.x_m) || !number(next_field(line), s.y_m) ||
      !number(next_field(line), s.yaw_rad)) {
    return std::nullopt;
  }
  s.robot = static_cast<uint32_t>(robot);
  // Optional columns, in order, until one is missing or not a number.
  double queue = 0;
  for (double* v : {&s.v_mps, &s.w_radps, &s.left_mps, &s.right_mps, &queue}) {
    if (line.empty() || !number(next_field(line), *v)) {
      *v = 0;
      break;
    }
  }
  s.queue = queue >= 0 ? static_cast<uint32_t>(std::min(queue, 1e6)) : 0;
  return s;
}

void for_each_state_row(std::string_view text, const std::function<void(const StateRow&)>& row) {
  rows_of(text, [&](std::string_view line, std::size_t line_no) {
    const auto s = parse_state_line(line);
    if (!s) throw bad_row(kStatesCsv, line_no, "t_s,robot,x_m,y_m,yaw_rad,... numbers");
    row(*s);
  });
}

void append_row(std::string& out, const ProgressRow& r) {
  put(out, r.t_s);
  put(out, r.finished);
  put(out, r.total, '\n');
}

std::optional<ProgressRow> last_progress_row(std::string_view text) {
  const auto end = text.rfind('\n');
  if (end == std::string_view::npos) return std::nullopt;
  const auto start = text.rfind('\n', end == 0 ? 0 : end - 1);
  std::string_view line =
      text.substr(start == std::string_view::npos || start == end ? 0 : start + 1,
                  end - (start == std::string_view::npos || start == end ? 0 : start + 1));
  ProgressRow r;
  if (!number(next_field(line), r.t_s) || !number(next_field(line), r.finished) ||
      !number(next_field(line), r.total) || !line.empty() || r.finished > r.total) {
    return std::nullopt;  // the header, or not a row
  }
  return r;
}

std::string finished_csv(const std::vector<uint32_t>& finished) {
  std::string out(kFinishedHeader);
  out += '\n';
  for (std::size_t r = 0; r < finished.size(); ++r) {
    put(out, static_cast<uint32_t>(r));
    put(out, finished[r], '\n');
  }
  return out;
}

std::vector<uint32_t> parse_finished_csv(std::string_view text) {
  std::vector<uint32_t> out;
  if (text.substr(0, kFinishedHeader.size()) != kFinishedHeader) return {};
  bool ok = true;
  rows_of(text, [&](std::string_view line, std::size_t) {
    uint32_t robot = 0, finished = 0;
    ok = ok && number(next_field(line), robot) && number(next_field(line), finished) &&
         line.empty() && robot == out.size();
    out.push_back(finished);
  });
  return ok ? out : std::vector<uint32_t>{};
}

namespace {
template <class T>
bool optional_count(std::string_view f, std::optional<T>& out) {
  out.reset();
  if (f.empty()) return true;
  T v{};
  if (!number(f, v)) return false;
  out = v;
  return true;
}
}  // namespace

void append_row(std::string& out, const TaskRow& r) {
  put(out, r.task);
  put(out, r.source_task);
  put(out, r.robot);
  put(out, r.errands);
  put(out, r.errands_done);
  put(out, r.revealed_s);
  put(out, r.assigned_s);
  put(out, r.opened_s);
  put(out, r.finished_s);
  put(out, r.finished_s ? std::optional<double>(*r.finished_s - r.revealed_s) : std::nullopt);
  out += cells_text(r.cells);
  out.push_back('\n');
}

std::string cells_text(const std::vector<std::pair<int32_t, int32_t>>& cells) {
  std::string out;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i > 0) out.push_back(';');
    put(out, cells[i].first, ' ');
    put(out, cells[i].second, 0);
  }
  return out;
}

std::optional<std::vector<std::pair<int32_t, int32_t>>> parse_cells(std::string_view text) {
  std::vector<std::pair<int32_t, int32_t>> out;
  if (!cells_of(text, out)) return std::nullopt;
  return out;
}

std::vector<TaskRow> parse_tasks_csv(std::string_view text) {
  std::vector<TaskRow> out;
  rows_of(text, [&](std::string_view line, std::size_t line_no) {
    TaskRow r;
    std::optional<double> latency;
    if (!number(next_field(line), r.task) || !number(next_field(line), r.source_task) ||
        !optional_count(next_field(line), r.robot) || !number(next_field(line), r.errands) ||
        !number(next_field(line), r.errands_done) || !number(next_field(line), r.revealed_s) ||
        !optional_number(next_field(line), r.assigned_s) ||
        !optional_number(next_field(line), r.opened_s) ||
        !optional_number(next_field(line), r.finished_s) ||
        !optional_number(next_field(line), latency) || !cells_of(next_field(line), r.cells) ||
        !line.empty()) {
      throw bad_row(kTasksCsv, line_no,
                    std::string(kTasksHeader) + " (numbers, some empty; cells \"x y;x y\")");
    }
    out.push_back(r);
  });
  return out;
}

void append_row(std::string& out, const EventRow& r) {
  put(out, r.t_s);
  out += r.event;
  out += ',';
  put(out, r.task);
  put(out, r.robot);
  put(out, r.errand);
  for (const char c : r.detail) out += c == ',' ? ';' : (c == '\n' || c == '\r') ? ' ' : c;
  out += '\n';
}

void append_row(std::string& out, const ThroughputRow& r) {
  put(out, r.t_s);
  put(out, r.tasks_finished);
  put(out, r.tasks_last_min);
  put(out, r.planner_ms);
  put(out, r.kept_actions);
  put(out, r.robots_with_task, '\n');
}

std::vector<EventRow> parse_events_csv(std::string_view text) {
  std::vector<EventRow> out;
  rows_of(text, [&](std::string_view line, std::size_t line_no) {
    EventRow r;
    std::optional<uint64_t> robot, errand;
    const bool ok = number(next_field(line), r.t_s);
    r.event = std::string(next_field(line));
    if (!ok || r.event.empty() || !optional_count(next_field(line), r.task) ||
        !optional_count(next_field(line), robot) || !optional_count(next_field(line), errand) ||
        (robot && *robot > UINT32_MAX) || (errand && *errand > UINT32_MAX)) {
      throw bad_row(kEventsCsv, line_no, std::string(kEventsHeader) + " (t_s, a word, counts)");
    }
    if (robot) r.robot = static_cast<uint32_t>(*robot);
    if (errand) r.errand = static_cast<uint32_t>(*errand);
    r.detail = std::string(line);  // the rest: commas were written as ';'
    out.push_back(std::move(r));
  });
  return out;
}

std::vector<ThroughputRow> parse_throughput_csv(std::string_view text) {
  std::vector<ThroughputRow> out;
  rows_of(text, [&](std::string_view line, std::size_t line_no) {
    ThroughputRow r;
    if (!number(next_field(line), r.t_s) || !number(next_field(line), r.tasks_finished) ||
        !number(next_field(line), r.tasks_last_min) || !number(next_field(line), r.planner_ms) ||
        !number(next_field(line), r.kept_actions) ||
        !number(next_field(line), r.robots_with_task) || !line.empty()) {
      throw bad_row(kThroughputCsv, line_no, std::string(kThroughputHeader) + " numbers");
    }
    out.push_back(r);
  });
  return out;
}

void append_row(std::string& out, const SwitchRow& r) {
  put(out, r.time_s);
  put(out, r.x);
  put(out, r.y);
  put(out, r.first);
  put(out, r.second);
  put(out, r.first_seq);
  put(out, r.second_seq);
  put(out, r.anticipated ? 1 : 0, '\n');
}

namespace {

// The columns after `second`: both seqs (empty: not recorded) and anticipated (0 or 1).
bool switch_tail(std::string_view line, SwitchRow& r) {
  uint32_t anticipated = 0;
  if (std::count(line.begin(), line.end(), ',') != 2 ||
      !optional_number(next_field(line), r.first_seq) ||
      !optional_number(next_field(line), r.second_seq) || !number(next_field(line), anticipated) ||
      anticipated > 1) {
    return false;
  }
  r.anticipated = anticipated == 1;
  return true;
}

}  // namespace

std::vector<SwitchRow> parse_switches_csv(std::string_view text) {
  std::vector<SwitchRow> out;
  rows_of(text, [&](std::string_view line, std::size_t line_no) {
    SwitchRow r;
    if (!number(next_field(line), r.time_s) || !number(next_field(line), r.x) ||
        !number(next_field(line), r.y) || !number(next_field(line), r.first) ||
        !number(next_field(line), r.second) || r.time_s < 0 || r.x < 0 || r.y < 0 ||
        (!line.empty() && !switch_tail(line, r))) {
      throw bad_row(kSwitchesCsv, line_no,
                    std::string(kSwitchesHeader) +
                        " (time and cells >= 0, robot ids, action seqs or empty, anticipated 0 or "
                        "1; the last three may be left out)");
    }
    out.push_back(r);
  });
  return out;
}

}  // namespace smart::results
