// Contract: who may speak for which robot on the per-robot topics, progress and states
// (idl/smart.idl, "Runs"; issue 25: "an insider key is its robot's only"). A writer in the run's
// own partition (a sim host) speaks for any robot; a writer in robot partitions for those robots
// only; a writer in any other partition (the "smart.run.*" wildcard, another run's robot, a
// malformed name) for none. Under DDS Security an agent-<id> identity may create writers only
// in its robot's partition (security/keystore.hpp), and readers check that against the signed
// permissions of the remote participant (Cyclone's access control, check_remote_datawriter), so
// its key moves its robot alone. Pure: a writer admission (admission.hpp) applies it to each
// sample in the receive path.
#pragma once

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace smart::dds {

// The robot whose partition `partition` is in the run of `run_partition`, or nothing.
std::optional<uint32_t> robot_of_partition(const std::string& run_partition,
                                           const std::string& partition);

struct Speaks {
  bool any = false;           // the run's own partition: a sim host
  std::set<uint32_t> robots;  // robot partitions
};
Speaks speaks_for(const std::string& run_partition, const std::vector<std::string>& partitions);
bool may_speak(const Speaks& speaks, uint32_t robot);
// Why a writer that speaks so may not speak for `robot`, or "".
std::string why_not(const Speaks& speaks, uint32_t robot);
// Why its samples for robots it does not speak for were refused.
std::string speaks_only(const Speaks& speaks);

}  // namespace smart::dds
