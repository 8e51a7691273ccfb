// Contract: who owns a run (idl/smart.idl, "Ownership"), decided without DDS: the ownership
// strength of a monitor's writers from its start time, and which of the monitors announced in a
// run owns it. Pure and deterministic.
// - A monitor's strength falls with its start time (10 ms steps, within [MONITOR_STRENGTH_MIN,
//   MONITOR_STRENGTH_RESUME - 1]; it wraps every ~124 days, then for one instant a later
//   monitor would rank first), so the monitor that came first keeps the fleet; --resume takes
//   MONITOR_STRENGTH_RESUME.
// - Among announced monitors the strongest owns; equal strengths: the smaller monitor_id.
#pragma once

#include <cstdint>
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

}  // namespace smart::wire
