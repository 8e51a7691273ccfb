// Contract: the results folder of a run (`smart run --out DIR`), specified once: its file names,
// the columns of each CSV, the summary.json keys other programs read, and a writer and a reader
// for each CSV's rows. The monitor writes through it (monitor/src/results.cpp), `smart serve`
// reads through it (replays, the robot panel, the progress plot, uploads; the web app downloads
// the files the server lists from kFiles), `smart experiment` collects summaries by kSummaryJson.
// New outputs are added here first.
// - Numbers are written as printf's %.10g (std::to_chars, general, 10 digits); an empty field is a
//   value that is not known (a robot that did not finish, an action that never finished, a bound
//   without the robot's limits).
// - Readers take the whole text, skip the header line and empty lines, and throw
//   std::invalid_argument naming the file, the line and what a row must hold. Pure: text in, text
//   out, no files.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace smart::results {

inline constexpr std::string_view kSummaryJson = "summary.json";
inline constexpr std::string_view kStatsCsv = "stats.csv";
inline constexpr std::string_view kRobotsCsv = "robots.csv";
inline constexpr std::string_view kActionsCsv = "actions.csv";
inline constexpr std::string_view kStatesCsv = "states.csv";
// Written while a run goes, for live views (`smart serve`); not a result (the finished run's
// progress comes from actions.csv).
inline constexpr std::string_view kProgressCsv = "progress.csv";
// Also for live views: each robot's finished actions, replaced whole about once a second.
inline constexpr std::string_view kFinishedCsv = "finished.csv";
// Every file of a results folder that a viewer lists, downloads or replays, in that order.
inline constexpr std::string_view kTasksCsv = "tasks.csv";
inline constexpr std::string_view kEventsCsv = "events.csv";
inline constexpr std::string_view kThroughputCsv = "throughput.csv";
// A switchable run's switches of passing orders (issue 29): time_s, x, y (the location, cells;
// .5 on an edge midpoint), first (the robot that passed first), second (the one planned first),
// first_seq, second_seq (the robots' actions entering the location: which visits; empty when not
// recorded), anticipated (1: made by expected times, switchable-opt and -lookahead); the last
// three absent in files written before 2026-12-02.
inline constexpr std::string_view kSwitchesCsv = "switches.csv";
inline constexpr std::string_view kSwitchesHeader =
    "time_s,x,y,first,second,first_seq,second_seq,anticipated";
inline constexpr std::array<std::string_view, 9> kFiles = {
    kSummaryJson, kStatsCsv,  kRobotsCsv,     kActionsCsv, kStatesCsv,
    kTasksCsv,    kEventsCsv, kThroughputCsv, kSwitchesCsv};
bool is_results_file(std::string_view name);
// The number a reader of these files gets back for v: v written as above (10 digits) and read
// again (a recording made while the run goes records what the files hold).
double as_written(double v);
// A sim host's own report of a run started by `smart run` (one per shard): sim-<shard>.json,
// the JSON line `smart sim` prints last on its standard output. Its keys that others read:
std::string sim_report_name(uint32_t shard);
namespace sim_report_key {
inline constexpr const char* kOk = "ok";
inline constexpr const char* kError = "error";
inline constexpr const char* kSimTimeS = "sim_time_s";
inline constexpr const char* kRobotContacts = "robot_contacts";  // this host's robots' episodes
inline constexpr const char* kWallContacts = "wall_contacts";
inline constexpr const char* kHandoversIn = "handovers_in";
}  // namespace sim_report_key
struct SimReport {
  bool ok = false;
  std::string error;
  double sim_time_s = 0;
  uint64_t robot_contacts = 0, wall_contacts = 0;
  uint64_t handovers_in = 0;
};
// The last non-empty line of the text as a report; throws std::invalid_argument naming `source`
// and the key that is missing or of the wrong type.
SimReport parse_sim_report(std::string_view text, const std::string& source);

// summary.json keys that programs other than a person read (every key: monitor/results.hpp and
// the README's paragraph on results).
namespace summary_key {
inline constexpr const char* kRobots = "robots";  // fleet size
inline constexpr const char* kSuccess = "success";
inline constexpr const char* kCellM = "cell_m";
inline constexpr const char* kFiles = "files";  // {map, scen, plan, robot}: the run's inputs
inline constexpr const char* kMap = "map";
inline constexpr const char* kScen = "scen";
inline constexpr const char* kPlan = "plan";      // also the plan object: {axis, ...}
inline constexpr const char* kRobot = "robot";    // in "files"
inline constexpr const char* kAxis = "axis";      // in "plan"
inline constexpr const char* kFormat = "format";  // in "plan"
inline constexpr const char* kRunId = "run_id";   // the run's id on the wire (samples carry it)
// How the run ended (monitor/run_supervisor.hpp Outcome), and the outcome of a run stopped
// before its end (a signal, or the monitor quit): what it had then, not a result (`smart
// experiment` runs such a cell again).
inline constexpr const char* kOutcome = "outcome";
inline constexpr const char* kOutcomeStopped = "stopped";
// A lifelong run's object and the keys of it that `smart experiment` reads.
inline constexpr const char* kLifelong = "lifelong";
inline constexpr const char* kTasksFinished = "tasks_finished";
inline constexpr const char* kThroughputPerMin = "throughput_per_min";
// The execution object (`smart run --execution`), read by the viewer (web/src/replay.js): its
// mode, switches made, how many anticipated, and a switching one's knobs (results.hpp
// switch_options_json).
inline constexpr const char* kExecution = "execution";
inline constexpr const char* kMode = "mode";  // in "execution"
inline constexpr const char* kSwitches = "switches";
inline constexpr const char* kAnticipated = "anticipated";
inline constexpr const char* kOptions = "options";
}  // namespace summary_key

// SMART's stats columns (smart-mapf/SMART server/src/ADG_server.cpp saveStats), in SMART's
// order. SMART writes wall-clock seconds under "time finish sim" and "sum finish time"; here they
// hold sim seconds, so they are named for what they hold.
inline constexpr std::string_view kStatsHeader =
    "steps finish sim,sum of steps finish sim,makespan sim s,sum of finish times sim s,"
    "original plan cost,#type-2 edges,#type-1 edges,#Nodes,#Move,#Rotate,"
    "#Consecutive Move,#Agent pair,instance name,number of agent";

// robots.csv: one row per robot.
inline constexpr std::string_view kRobotsHeader =
    "robot,finish_time_s,waiting_time_s,stops,actions,lower_bound_s";
struct RobotRow {
  uint32_t robot = 0;
  std::optional<double> finish_time_s;  // none: not finished, or done before a resume
  double waiting_time_s = 0;
  uint64_t stops = 0;
  uint64_t actions = 0;
  std::optional<double> lower_bound_s;  // none: the robot's limits were not known
};
void append_row(std::string& out, const RobotRow& row);
std::vector<RobotRow> parse_robots_csv(std::string_view text);

// actions.csv: one row per action, in ADG order.
inline constexpr std::string_view kActionsHeader = "robot,action,type,finish_time_s";
enum class ActionType { kMove, kRotate };  // written "move", "rotate"
struct ActionRow {
  uint32_t robot = 0;
  uint32_t action = 0;  // the robot's action seq
  ActionType type = ActionType::kMove;
  std::optional<double> finish_time_s;  // sim time; none: never finished, or before a resume
};
void append_row(std::string& out, const ActionRow& row);
// Calls `row` for each row with its line number (for the caller's own checks).
void for_each_action_row(std::string_view text,
                         const std::function<void(const ActionRow&, std::size_t line)>& row);

// states.csv: robot states as the monitor received them, written row by row while a run goes.
inline constexpr std::string_view kStatesHeader =
    "t_s,robot,x_m,y_m,yaw_rad,v_mps,omega_radps,left_mps,right_mps,queue";
struct StateRow {
  double t_s = 0;
  uint32_t robot = 0;
  double x_m = 0, y_m = 0, yaw_rad = 0, v_mps = 0, w_radps = 0, left_mps = 0, right_mps = 0;
  uint32_t queue = 0;
};
void append_row(std::string& out, const StateRow& row);
// One line without its newline; none when it is not a row (a live file's partial line).
std::optional<StateRow> parse_state_line(std::string_view line);
// Rows need t_s, robot, x_m, y_m, yaw_rad (finite; robot up to 10^7); the other columns are read
// when present (files of older versions lack some) and 0 otherwise.
void for_each_state_row(std::string_view text, const std::function<void(const StateRow&)>& row);

// progress.csv: finished actions as the run goes, a row when the count changed (at most ten a
// second of wall time), so a live view shows the run's progress (issue 26).
inline constexpr std::string_view kProgressHeader = "t_s,finished,total";
struct ProgressRow {
  double t_s = 0;  // sim time
  uint64_t finished = 0, total = 0;
};
void append_row(std::string& out, const ProgressRow& row);
// The last complete row of a growing file's text (its header and a partial last line skipped);
// none when there is none.
std::optional<ProgressRow> last_progress_row(std::string_view text);

// finished.csv: "robot,finished" then a row per robot in order (a live robot panel's current
// action is its finished count; whom it waits for, the others' counts).
inline constexpr std::string_view kFinishedHeader = "robot,finished";
std::string finished_csv(const std::vector<uint32_t>& finished);
// The counts by robot; empty when the text is not such a file (e.g. torn).
std::vector<uint32_t> parse_finished_csv(std::string_view text);

// Lifelong runs (`smart run --lifelong`, lifelong/): three more files (kTasksCsv, kEventsCsv,
// kThroughputCsv), streamed while the run goes, and the map the run was made on, written beside
// them (a LoRR problem's map is not the file summary.json names).
inline constexpr std::string_view kLifelongMap = "lifelong.map";

// tasks.csv: a row per task once it finished (and, at the run's end, every task still open).
// latency_s = finished_s - revealed_s (LoRR's task latency); empty fields: not (yet) happened.
// cells: the errands' cells in order, "x y" pairs (MovingAI column and row) separated by ';'.
inline constexpr std::string_view kTasksHeader =
    "task,source_task,robot,errands,errands_done,revealed_s,assigned_s,opened_s,finished_s,"
    "latency_s,cells";
struct TaskRow {
  uint64_t task = 0;         // revealed order (LoRR's task_id)
  uint32_t source_task = 0;  // line of the tasks file / generated task it repeats
  std::optional<uint32_t> robot;
  uint32_t errands = 0, errands_done = 0;
  double revealed_s = 0;
  std::optional<double> assigned_s, opened_s, finished_s;
  std::vector<std::pair<int32_t, int32_t>> cells = {};  // the errands' (x, y), in order
};
void append_row(std::string& out, const TaskRow& row);
std::vector<TaskRow> parse_tasks_csv(std::string_view text);
// A task's cells as tasks.csv writes them ("x y;x y"), and back (nothing: malformed).
std::string cells_text(const std::vector<std::pair<int32_t, int32_t>>& cells);
std::optional<std::vector<std::pair<int32_t, int32_t>>> parse_cells(std::string_view text);

// events.csv: what happened to tasks and windows, in order. event: revealed (detail: its errand
// cells as in tasks.csv, so a running run's tasks can be drawn), assigned, opened (first errand
// done), errand (a later errand done), finished, window (a plan appended), refused (a window
// refused: detail says why). task/robot/errand empty where they do not apply.
inline constexpr std::string_view kEventsHeader = "t_s,event,task,robot,errand,detail";
struct EventRow {
  double t_s = 0;
  std::string event;
  std::optional<uint64_t> task;
  std::optional<uint32_t> robot;
  std::optional<uint32_t> errand;
  std::string detail;  // commas and newlines replaced by ';' and ' '
};
void append_row(std::string& out, const EventRow& row);
std::vector<EventRow> parse_events_csv(std::string_view text);

// throughput.csv: a row per planning call: tasks finished so far and over the last sim minute,
// the planner's wall time, the actions kept by the commit cut, robots with a task.
inline constexpr std::string_view kThroughputHeader =
    "t_s,tasks_finished,tasks_last_min,planner_ms,kept_actions,robots_with_task";
struct ThroughputRow {
  double t_s = 0;
  uint64_t tasks_finished = 0, tasks_last_min = 0;
  double planner_ms = 0;
  uint64_t kept_actions = 0, robots_with_task = 0;
};
void append_row(std::string& out, const ThroughputRow& row);
std::vector<ThroughputRow> parse_throughput_csv(std::string_view text);

// switches.csv (kSwitchesHeader): a row per switch of a passing order (issue 29): when, where (in
// cells, .5 on an edge midpoint), the robot that passed first and the robot planned first, and
// the seq of each one's action entering the location (written by every switchable plan run),
// and whether it was anticipated; rows of the five older columns are read without them. The
// live file a run appends to (monitor --out) is what `monitor --resume --resume-switches`
// replays.
struct SwitchRow {
  double time_s = 0;
  double x = 0, y = 0;
  uint32_t first = 0, second = 0;
  std::optional<uint32_t> first_seq = {}, second_seq = {};
  bool anticipated = false;
};
void append_row(std::string& out, const SwitchRow& row);
// Throws std::invalid_argument naming the line of a malformed row (times and cells >= 0).
std::vector<SwitchRow> parse_switches_csv(std::string_view text);

}  // namespace smart::results
