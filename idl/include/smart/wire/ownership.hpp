// Contract: who owns a run (idl/smart.idl, "Ownership"), decided without DDS: the ownership
// strength of a monitor's writers from its start time, and which of the monitors announced in a
// run owns it. Pure and deterministic.
// - A monitor's strength falls with its start time (10 ms steps, within [MONITOR_STRENGTH_MIN,
//   MONITOR_STRENGTH_RESUME - 1]; it wraps every ~124 days, then for one instant a later
//   monitor would rank first), so the monitor that came first keeps the fleet; --resume takes
//   MONITOR_STRENGTH_RESUME.
// - Among announced monitors the strongest owns; equal strengths: the smaller monitor_id; but a
//   --resume monitor never outranks a live monitor that is not resuming (resume takes over only
//   a run whose monitor is gone).
// - ClaimBook (issue 25, "one sample stops every run"): the announcements heard. A claim is live
//   once heard twice (a monitor re-announces every second: one sample, replayed or forged, is
//   not a monitor) and last heard within kClaimLiveS; a claim gone quiet is dropped. At most
//   kMaxClaims are kept (a flood of made-up monitors evicts the longest quiet).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace smart::wire {

int32_t monitor_strength(uint64_t unix_time_ms, bool resume);

struct MonitorClaim {
  uint64_t monitor_id = 0;
  uint64_t run_id = 0;
  std::string host;
  int32_t pid = 0;
  int32_t strength = 0;
  bool resume = false;
};

bool outranks(const MonitorClaim& a, const MonitorClaim& b);
// The claim among `others` that outranks `self`, if any (the strongest of them).
std::optional<MonitorClaim> owner_over(const MonitorClaim& self,
                                       const std::vector<MonitorClaim>& others);
// "monitor on host H (pid P, run R)"
std::string describe(const MonitorClaim& claim);

inline constexpr double kClaimLiveS = 2.5;
inline constexpr std::size_t kMaxClaims = 64;

class ClaimBook {
 public:
  void heard(const MonitorClaim& claim, double now_s);
  void gone(uint64_t monitor_id) { heard_.erase(monitor_id); }
  std::vector<MonitorClaim> live(double now_s) const;
  // A claim heard once, recently: worth waiting for (it repeats if its monitor is alive).
  bool pending(double now_s) const;

 private:
  struct Heard {
    MonitorClaim claim;
    int times = 0;
    double last_s = 0;
  };
  std::map<uint64_t, Heard> heard_;
};

}  // namespace smart::wire
