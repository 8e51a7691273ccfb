// Contract: the closest approach between robots as their reported poses (RobotState) show it,
// for robots no sim host watches: physical or emulated robots in a real-time run. (A sim host
// measures contacts from its physics, sim/contacts.hpp, and reports them in SimStatus.) Pure:
// poses in, numbers out; deterministic.
// - on_pose(robot, x, y, t_s) compares the robot with every robot whose last pose lies within
//   two diameters (4·radius, centre to centre; farther pairs are not compared) and was
//   reported within max_skew_s of t_s: older poses would compare where two robots were at
//   different times (agents report every control period, 25–100 ms; a sim host at
//   --state-rate-hz, too seldom to compare).
// - min_gap_m(): the smallest surface distance seen (centre distance − 2·radius; negative =
//   overlap); nothing until two robots came within 4·radius at about the same time.
// - contacts(): how often two robots came closer than a diameter (a pair counts again only
//   after it separated); first_contact(): the first such pair and when.
// Sampled poses are evidence, not proof: a contact between two samples is missed, and pose
// noise and latency (mocap: millimetres, tens of ms) shift the numbers by as much.
#pragma once

#include <cstdint>
#include <optional>
#include <set>
#include <unordered_map>
#include <utility>
#include <vector>

namespace smart::monitor {

struct PoseContact {
  uint32_t a = 0, b = 0;  // a < b
  double t_s = 0;
  double gap_m = 0;  // negative: overlap
};

class SeparationWatch {
 public:
  SeparationWatch(std::size_t robots, double radius_m, double max_skew_s = 0.1);

  // Ignores robots out of range and non-finite values.
  void on_pose(uint32_t robot, double x_m, double y_m, double t_s);

  std::optional<double> min_gap_m() const { return min_gap_m_; }
  uint64_t contacts() const { return contacts_; }
  const std::optional<PoseContact>& first_contact() const { return first_; }

 private:
  struct Last {
    double x_m = 0, y_m = 0, t_s = 0;
    int64_t bucket = 0;
    bool valid = false;
  };
  std::pair<int64_t, int64_t> bucket_of(double x_m, double y_m) const;
  void move_to_bucket(uint32_t robot, int64_t bucket);
  void compare(uint32_t robot, uint32_t other);
  void forget_separated(uint32_t robot);

  double radius_m_, reach_m_, max_skew_s_;
  std::vector<Last> last_;
  std::unordered_map<int64_t, std::vector<uint32_t>> buckets_;  // robots by 4·radius square
  std::set<std::pair<uint32_t, uint32_t>> touching_;
  std::optional<double> min_gap_m_;
  uint64_t contacts_ = 0;
  std::optional<PoseContact> first_;
};

}  // namespace smart::monitor
