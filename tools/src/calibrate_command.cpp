// `smart calibrate`: lab bring-up before a run.
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
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "smart/agent/wheel_trim.hpp"
#include "smart/dds/topics.hpp"
#include "smart/geometry/frame_transform.hpp"
#include "smart/grid/map_reader.hpp"
#include "smart/grid/text_file.hpp"
#include "smart/tools/cli_common.hpp"
#include "smart/tools/commands.hpp"
#include "smart/tools/robot_backends.hpp"

namespace smart::tools {

namespace {

struct Point {
  std::string id;  // robot index or object name, substituted for {id}
  int col = 0, row = 0;
};

struct FrameOptions {
  DdsOptions dds;
  std::string map, out;
  double cell_m = 1.0;
  std::vector<std::string> points;  // ID:COL,ROW
  PoseKind pose = PoseKind::kVicon;
  std::string vicon_bind = "0.0.0.0";
  uint16_t vicon_port = 51001;
  std::string vicon_object = "jetbot{id}";
  std::string ros_namespace{dds::kRosNamespacePattern};
  std::string ros_topic;
  double record_s = 1.0;
  double tolerance_m = 0.02;
};

Point parse_point(const std::string& text) {
  Point p;
  const auto colon = text.find(':');
  char comma = 0;
  std::istringstream cell(colon == std::string::npos ? "" : text.substr(colon + 1));
  if (colon == std::string::npos || colon == 0 || !(cell >> p.col >> comma >> p.row) ||
      comma != ',' || !cell.eof()) {
    throw std::invalid_argument("--point '" + text +
                                "': write ID:COL,ROW, e.g. 3:0,5 (robot 3 "
                                "stands on column 0, row 5 of the map)");
  }
  p.id = text.substr(0, colon);
  return p;
}

// Pose sources in the source's own units and frame (identity transform): what is fitted.
struct RawSources {
  std::unique_ptr<hw::ViconReceiver> vicon;
  std::vector<std::unique_ptr<agent::PoseSource>> sources;  // per point
};

RawSources open_raw_sources(const FrameOptions& o, const std::vector<Point>& points,
                            const dds::Participant& participant) {
  RawSources r;
  const geometry::FrameTransform identity;
  if (o.pose == PoseKind::kVicon) {
    std::vector<std::string> objects;
    for (const auto& p : points) objects.push_back(with_id(o.vicon_object, p.id));
    r.vicon = std::make_unique<hw::ViconReceiver>(o.vicon_bind, o.vicon_port, identity, objects,
                                                  steady_s);
    for (const auto& name : objects) {
      r.sources.push_back(std::make_unique<hw::ViconPoseSource>(*r.vicon, name, 1.0, steady_s));
    }
    return r;
  }
  for (const auto& p : points) {
    const bool odom = o.pose == PoseKind::kOdom;
    if (!odom && o.ros_topic.empty()) {
      throw std::invalid_argument("--pose ros needs --ros-topic ({id} is the point's ID)");
    }
    const auto topic =
        odom ? dds::ros_odom_topic(with_id(o.ros_namespace, p.id)) : with_id(o.ros_topic, p.id);
    r.sources.push_back(std::make_unique<hw::RosPoseSource>(
        participant, topic, identity, 1.0, steady_s,
        odom ? hw::RosPoseSource::Message::kOdometry : hw::RosPoseSource::Message::kPoseStamped));
  }
  return r;
}

// Mean position of each source over record_s (every new sample once).
std::vector<Eigen::Vector2d> record_means(const FrameOptions& o, const std::vector<Point>& points,
                                          RawSources& raw) {
  std::vector<Eigen::Vector2d> sum(points.size(), Eigen::Vector2d::Zero());
  std::vector<int> n(points.size(), 0);
  std::vector<double> last(points.size(), -1);
  const double end_s = steady_s() + o.record_s;
  for (double wait_until = steady_s() + 10.0; steady_s() < end_s || steady_s() < wait_until;) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto s = raw.sources[i]->read();
      if (!s.valid || s.stamp_s == last[i]) continue;
      last[i] = s.stamp_s;
      sum[i] += Eigen::Vector2d(s.pose.x_m, s.pose.y_m);
      ++n[i];
    }
    // Past record_s, wait (up to 10 s) only for points that have no pose yet.
    if (steady_s() >= end_s && std::all_of(n.begin(), n.end(), [](int k) { return k >= 3; })) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::vector<Eigen::Vector2d> means;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (n[i] < 3) {
      throw std::runtime_error("point " + points[i].id + ": " + std::to_string(n[i]) +
                               " poses in 10 s; check that its pose source is streaming");
    }
    means.push_back(sum[i] / n[i]);
  }
  return means;
}

nlohmann::json fit_report(const std::vector<Point>& points, const std::vector<Eigen::Vector2d>& src,
                          const geometry::SimilarityFit& fit, bool accepted, double tol) {
  nlohmann::json j = {
      {"accepted", accepted},
      {"tolerance_m", tol},
      {"scale", fit.transform.scale},
      {"yaw_rad", fit.transform.yaw_rad},
      {"translation_m", {fit.transform.translation_m.x(), fit.transform.translation_m.y()}},
      {"rms_m", fit.rms_m},
      {"max_m", fit.max_m},
      {"points", nlohmann::json::array()}};
  for (std::size_t i = 0; i < points.size(); ++i) {
    j["points"].push_back({{"id", points[i].id},
                           {"cell", {points[i].col, points[i].row}},
                           {"source", {src[i].x(), src[i].y()}},
                           {"residual_m", fit.residuals_m[i]}});
  }
  return j;
}

int run_frame(const FrameOptions& o) {
  const auto grid = grid::parse_map(grid::read_text_file(o.map, "map"), o.map);
  std::vector<Point> points;
  std::vector<Eigen::Vector2d> world;
  for (const auto& text : o.points) {
    const auto p = parse_point(text);
    if (!grid.inside({p.col, p.row})) {
      throw std::invalid_argument("--point '" + text + "': the cell is outside the " +
                                  std::to_string(grid.width()) + "x" +
                                  std::to_string(grid.height()) + " map " + o.map);
    }
    const auto w = grid.to_world({2 * p.col, 2 * p.row}, o.cell_m);
    world.emplace_back(w.x_m, w.y_m);
    for (const auto& q : points) {
      if (q.id == p.id) {
        throw std::invalid_argument("--point '" + text + "': " + p.id +
                                    " is already placed; each point is a different robot or "
                                    "object recorded at the same time");
      }
    }
    points.push_back(p);
  }
  const auto profile = run_qos_profile(o.dds);
  dds::Domain domain(o.dds.domain, domain_config(o.dds, profile, "calibrate"));
  dds::Participant participant(domain, o.dds.run);
  auto raw = open_raw_sources(o, points, participant);
  const auto src = record_means(o, points, raw);
  const auto fit = geometry::fit_similarity(src, world);
  const bool accepted = fit.max_m <= o.tolerance_m;
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::cerr << "point " << points[i].id << " cell (" << points[i].col << "," << points[i].row
              << "): residual " << fit.residuals_m[i] * 1000 << " mm"
              << (fit.residuals_m[i] > o.tolerance_m ? "  <-- over the tolerance" : "") << "\n";
  }
  if (accepted) {
    std::ofstream out(o.out);
    out << geometry::frame_transform_yaml(fit.transform, &fit, &src, &world);
    if (!out) throw std::runtime_error(o.out + ": cannot write the transform file");
  } else {
    spdlog::error(
        "fit refused: largest residual {:.1f} mm exceeds --tolerance-m {} ({} not "
        "written); check the cells of the points marked above, or move them",
        fit.max_m * 1000, o.tolerance_m, o.out);
  }
  std::cout << fit_report(points, src, fit, accepted, o.tolerance_m).dump() << std::endl;
  return accepted ? kExitSuccess : kExitRunFailed;
}

struct TrimOptions {
  DdsOptions dds;
  BackendOptions io;
  uint32_t robot_id = 0;
  double speed_mps = 0.15;
  double seconds = 3.0;
  double settle_s = 0.5;
  bool yes = false;
};

bool confirmed(const TrimOptions& o) {
  if (o.yes) return true;
  std::cerr << "Robot " << o.robot_id << " will drive straight ahead for " << o.seconds << " s at "
            << o.speed_mps << " m/s (about " << o.seconds * o.speed_mps
            << " m): clear the way. Type yes to go: " << std::flush;
  std::string answer;
  std::getline(std::cin, answer);
  return answer == "yes";
}

// Drives both wheels at speed_mps for `seconds` (commands at 50 Hz keep the JetBot's command
// watchdog fed) and returns every new pose sample; the wheels stop at the end.
std::vector<agent::PoseSample> drive_straight(const TrimOptions& o, RobotIo& io) {
  std::vector<agent::PoseSample> samples;
  auto ready = io.drive->configure();
  if (ready.ok()) ready = io.drive->activate();
  if (!ready.ok()) throw std::runtime_error(ready.message);
  double last_stamp = -1;
  const double start_s = steady_s(), first_pose_deadline_s = start_s + 5.0;
  for (double now = start_s; now < start_s + o.seconds && !g_stop_requested; now = steady_s()) {
    const auto p = io.pose->read();
    if (p.valid && p.stamp_s != last_stamp) {
      samples.push_back(p);
      last_stamp = p.stamp_s;
    }
    if (samples.empty() && now > first_pose_deadline_s) break;
    io.drive->set_wheel_speeds(samples.empty() ? agent::WheelSpeeds{}
                                               : agent::WheelSpeeds{o.speed_mps, o.speed_mps});
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (auto r = io.drive->deactivate(); !r.ok()) throw std::runtime_error(r.message);
  if (g_stop_requested) throw std::runtime_error("stopped by signal; the wheels are off");
  if (samples.empty()) {
    throw std::runtime_error("robot " + std::to_string(o.robot_id) + ": no pose from " +
                             io.pose_name + " in 5 s; check the pose stream");
  }
  return samples;
}

nlohmann::json trim_proposal(const TrimOptions& o, const agent::WheelTrial& t,
                             const agent::RobotModel& model, const RobotIo& io) {
  nlohmann::json j = {{"robot_id", o.robot_id},
                      {"speed_mps", t.speed_mps},
                      {"turn_rate_radps", t.turn_rate_radps},
                      {"gain", {{"left", t.gain.left}, {"right", t.gain.right}}},
                      {"trim", {{"left", t.trim.left}, {"right", t.trim.right}}}};
  std::ostringstream yaml;
  if (io.jetbot != nullptr) {  // the board's per-wheel alpha is the JetBot's trim
    const double left = io.hardware.left.alpha * t.trim.left;
    const double right = io.hardware.right.alpha * t.trim.right;
    yaml << "hardware:\n  left: {alpha: " << left << "}\n  right: {alpha: " << right << "}\n";
    j["proposed"] = {{"hardware.left.alpha", left}, {"hardware.right.alpha", right}};
  } else {
    const double left = model.trim.left * t.trim.left, right = model.trim.right * t.trim.right;
    yaml << "trim: {left: " << left << ", right: " << right << "}\n";
    j["proposed"] = {{"trim.left", left}, {"trim.right", right}};
  }
  std::cerr << "Measured: " << t.speed_mps << " m/s, turning " << t.turn_rate_radps
            << " rad/s; wheel gains left " << t.gain.left << ", right " << t.gain.right
            << ".\nPut this in the robot file (keep its other keys):\n"
            << yaml.str();
  return j;
}

int run_trim(const TrimOptions& o) {
  const auto file = robot_file(o.io);
  const auto model = agent::load_robot_model(file);
  const auto profile = run_qos_profile(o.dds);
  dds::Domain domain(o.dds.domain,
                     domain_config(o.dds, profile, "agent-" + std::to_string(o.robot_id)));
  dds::Participant participant(domain, o.dds.run);
  auto io = open_robot(o.io, o.robot_id, model, file, participant);
  const auto signal_stop = stop_outputs_on_signal(io);
  if (!confirmed(o)) {
    spdlog::error("not confirmed: the robot did not move (answer yes, or pass --yes)");
    return kExitRunFailed;
  }
  const auto samples = drive_straight(o, io);
  const auto trial =
      agent::measure_wheel_trial(samples, o.speed_mps, model.wheel_base_m, o.settle_s);
  std::cout << trim_proposal(o, trial, model, io).dump() << std::endl;
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
  add_enum_option(cmd, "--pose", o->pose, kinds,
                  "vicon (Tracker UDP; default), odom (<ns>/odom) or ros (PoseStamped)");
  cmd->add_option("--vicon-bind", o->vicon_bind)->capture_default_str();
  cmd->add_option("--vicon-port", o->vicon_port)->capture_default_str();
  cmd->add_option("--vicon-object", o->vicon_object, "Vicon object of a point; {id} is its ID")
      ->capture_default_str();
  cmd->add_option("--ros-namespace", o->ros_namespace, "namespace of a point for --pose odom")
      ->capture_default_str();
  cmd->add_option("--ros-topic", o->ros_topic, "PoseStamped topic for --pose ros; {id}: the ID");
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
  cmd->add_option("--speed-mps", o->speed_mps, "commanded speed of both wheels")
      ->check(finite_in(0.02, 2.0))
      ->capture_default_str();
  cmd->add_option("--seconds", o->seconds, "how long to drive")
      ->check(finite_in(1.0, 60.0))
      ->capture_default_str();
  cmd->add_option("--settle-s", o->settle_s, "poses ignored at the start (acceleration)")
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
