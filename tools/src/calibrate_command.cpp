// `smart calibrate`: lab bring-up before a run; the procedures are commissioning/calibration.hpp.
// - `calibrate frame`: robots (or mocap objects) stand on known cells; their poses are recorded
//   for --record-s from the pose source (Vicon, odometry, a PoseStamped), averaged, and the
//   similarity from the source's frame to the grid is fitted (Umeyama, common/geometry). The
//   residual of every point is reported; a fit whose largest residual exceeds --tolerance-m is
//   refused (exit 1, nothing written), otherwise the transform file that `smart agent
//   --pose-transform` reads is written.
// - `calibrate trim`: one robot drives straight (both wheels commanded alike) for --seconds, its
//   poses are recorded, and per-wheel gains and the trim that makes it drive straight are
//   proposed (agent/wheel_trim.hpp) as YAML for the robot file: the JetBot's hardware alpha, a
//   ROS 2 base's `trim:`. It asks before moving unless --yes.
#include <spdlog/spdlog.h>

#include <chrono>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "smart/commissioning/calibration.hpp"
#include "smart/grid/map_reader.hpp"
#include "smart/grid/text_file.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"
#include "smart/tools/robot_backends.hpp"

namespace smart::tools {

namespace {

struct FrameOptions {
  DdsOptions dds;
  std::string map, out;
  double cell_m = 1.0;
  std::vector<std::string> points;  // ID:COL,ROW
  commissioning::FrameSources sources;
  double record_s = 1.0;
  double tolerance_m = 0.02;
};

int run_frame(const FrameOptions& o) {
  const auto grid = grid::parse_map(grid::read_text_file(o.map, "map"), o.map);
  const auto points = commissioning::place_points(o.points, grid, o.cell_m, o.map);
  const auto profile = run_qos_profile(o.dds);
  dds::Domain domain(o.dds.domain, domain_config(o.dds, profile, "calibrate"));
  dds::Participant participant(domain, o.dds.run);
  const auto f =
      commissioning::fit_frame(o.sources, points, o.record_s, o.tolerance_m, participant);
  std::vector<Eigen::Vector2d> world;
  for (std::size_t i = 0; i < points.size(); ++i) {
    world.push_back(points[i].world_m);
    std::cerr << "point " << points[i].id << " cell (" << points[i].col << "," << points[i].row
              << "): residual " << f.fit.residuals_m[i] * 1000 << " mm"
              << (f.fit.residuals_m[i] > o.tolerance_m ? "  <-- over the tolerance" : "") << "\n";
  }
  if (f.accepted) {
    std::ofstream out(o.out);
    out << geometry::frame_transform_yaml(f.fit.transform, &f.fit, &f.source, &world);
    if (!out) throw std::runtime_error(o.out + ": cannot write the transform file");
  } else {
    spdlog::error(
        "fit refused: largest residual {:.1f} mm exceeds --tolerance-m {} ({} not "
        "written); check the cells of the points marked above, or move them",
        f.fit.max_m * 1000, o.tolerance_m, o.out);
  }
  std::cout << f.report(points, o.tolerance_m).dump() << std::endl;
  return f.accepted ? kExitSuccess : kExitRunFailed;
}

struct TrimOptions {
  DdsOptions dds;
  BackendOptions io;
  uint32_t robot_id = 0;
  commissioning::TrimTrial trial;
  bool yes = false;
};

bool confirmed(const TrimOptions& o) {
  if (o.yes) return true;
  std::cerr << "Robot " << o.robot_id << " will drive straight ahead for " << o.trial.seconds
            << " s at " << o.trial.speed_mps << " m/s (about "
            << o.trial.seconds * o.trial.speed_mps
            << " m): clear the way. Type yes to go: " << std::flush;
  std::string answer;
  std::getline(std::cin, answer);
  return answer == "yes";
}

int run_trim(const TrimOptions& o) {
  const auto file = hw::robot_file(o.io);
  const auto model = agent::load_robot_model(file);
  const auto profile = run_qos_profile(o.dds);
  dds::Domain domain(o.dds.domain,
                     domain_config(o.dds, profile, "agent-" + std::to_string(o.robot_id)));
  dds::Participant participant(domain, o.dds.run);
  auto io = hw::open_robot(o.io, o.robot_id, model, file, participant);
  const auto signal_stop = hw::stop_outputs_on_signal(io, &g_stop_requested);
  if (!confirmed(o)) {
    spdlog::error("not confirmed: the robot did not move (answer yes, or pass --yes)");
    return kExitRunFailed;
  }
  // Said once the signal handler is in place: a person (or a test) knows Ctrl-C now stops it.
  std::cerr << "Robot " << o.robot_id << " driving for " << o.trial.seconds
            << " s; Ctrl-C stops the wheels." << std::endl;
  auto trial = o.trial;
  trial.stop = &g_stop_requested;
  const auto samples = commissioning::drive_straight(trial, o.robot_id, io);
  const auto measured =
      agent::measure_wheel_trial(samples, trial.speed_mps, model.wheel_base_m, trial.settle_s);
  const auto p = commissioning::propose_trim(o.robot_id, measured, model, io);
  std::cerr << "Measured: " << measured.speed_mps << " m/s, turning " << measured.turn_rate_radps
            << " rad/s; wheel gains left " << measured.gain.left << ", right "
            << measured.gain.right << ".\nPut this in the robot file (keep its other keys):\n"
            << p.yaml;
  std::cout << p.report.dump() << std::endl;
  return kExitSuccess;
}

void add_frame_command(CLI::App* parent, int& exit_code) {
  auto o = std::make_shared<FrameOptions>();
  auto* cmd = parent->add_subcommand(
      "frame", "Fit the pose source's frame to the grid from robots or objects on known cells");
  add_dds_options(cmd, o->dds);
  cmd->add_option("--map", o->map, "the map the cells are on")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--cell-m", o->cell_m, "cell size in metres")
      ->check(finite_in(0.01, 100.0))
      ->capture_default_str();
  cmd->add_option("--point", o->points,
                  "ID:COL,ROW - the robot or object ID stands on that cell (3 or more, not in a "
                  "row)")
      ->required();
  const EnumNames<PoseKind> kinds{
      {"vicon", PoseKind::kVicon}, {"odom", PoseKind::kOdom}, {"ros", PoseKind::kRos}};
  add_enum_option(cmd, "--pose", o->sources.pose, kinds,
                  "vicon (Tracker UDP; default), odom (<ns>/odom) or ros (PoseStamped)");
  cmd->add_option("--vicon-bind", o->sources.vicon_bind,
                  "local IPv4 address the Vicon socket listens on")
      ->capture_default_str();
  cmd->add_option("--vicon-port", o->sources.vicon_port,
                  "UDP port of the Vicon stream (0: the first free port below 7400)")
      ->capture_default_str();
  cmd->add_option("--vicon-object", o->sources.vicon_object,
                  "Vicon object of a point; {id} is its ID")
      ->capture_default_str();
  cmd->add_option("--ros-namespace", o->sources.ros_namespace,
                  "namespace of a point for --pose odom")
      ->capture_default_str();
  cmd->add_option("--ros-topic", o->sources.ros_topic,
                  "PoseStamped topic for --pose ros; {id}: the ID");
  cmd->add_option("--record-s", o->record_s, "how long to average each point's poses")
      ->check(finite_in(0.05, 60.0))
      ->capture_default_str();
  cmd->add_option("--tolerance-m", o->tolerance_m, "largest residual accepted")
      ->check(finite_in(1e-6, 10.0))
      ->capture_default_str();
  cmd->add_option("--out", o->out, "the transform file to write")->required();
  cmd->callback([&exit_code, o] { exit_code = run_frame(*o); });
}

void add_trim_command(CLI::App* parent, int& exit_code) {
  auto o = std::make_shared<TrimOptions>();
  auto* cmd = parent->add_subcommand(
      "trim", "Drive one robot straight, measure its drift, propose wheel trim for its file");
  add_dds_options(cmd, o->dds);
  cmd->add_option("--robot-id", o->robot_id, "the robot")->required();
  add_backend_options(cmd, o->io);
  cmd->add_option("--speed-mps", o->trial.speed_mps, "commanded speed of both wheels")
      ->check(finite_in(0.02, 2.0))
      ->capture_default_str();
  cmd->add_option("--seconds", o->trial.seconds, "how long to drive")
      ->check(finite_in(1.0, 60.0))
      ->capture_default_str();
  cmd->add_option("--settle-s", o->trial.settle_s, "poses ignored at the start (acceleration)")
      ->check(finite_in(0.0, 10.0))
      ->capture_default_str();
  cmd->add_flag("--yes", o->yes, "do not ask before moving");
  cmd->callback([&exit_code, o] {
    install_stop_handlers();
    exit_code = run_trim(*o);
  });
}

}  // namespace

void register_calibrate_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("calibrate", "Lab bring-up: fit the mocap frame, trim the wheels");
  cmd->require_subcommand(1);
  add_frame_command(cmd, exit_code);
  add_trim_command(cmd, exit_code);
}

}  // namespace smart::tools
