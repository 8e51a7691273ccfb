// Contract: SMART-DDS's DDS Security keystore (OMG DDS Security 1.1 builtin plugins), made by
// `smart security init --out DIR` with the openssl command (Debian):
//   DIR/ca.pem, DIR/ca.key         one CA for identities and permissions (ca.key stays 0600)
//   DIR/governance.p7s             every domain: authentication required, join access control,
//                                  discovery, liveliness and every topic's data encrypted
//   DIR/<identity>/{cert.pem, key.pem, permissions.p7s}
// Identities and what their permissions allow (topics of idl/smart.idl, any run partition):
//   monitor   publishes actions, clock answers, its MonitorInfo, a lifelong run's planning
//             problem and requests; reads the rest
//   planner   publishes its PlannerInfo and plan replies; reads the problem and requests
//   sim       publishes progress, states, ticks, sim status and the ROS 2 view (rt/*)
//   agent-<id> (one per robot id) publishes progress and states; reads actions and the clock
//   viewer    reads everything, publishes nothing
// A ROS 2 user's SROS2 keystore has the same pieces (README, "Running safely on a shared
// network"). Pure text here (governance_xml, permissions_xml, grants); files and openssl in
// init_keystore(); identity_files() finds one identity's files or says what is missing.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "smart/dds/domain.hpp"

namespace smart::security {

struct Grant {
  std::string identity;  // directory name and CN
  std::vector<std::string> publish;
  std::vector<std::string> subscribe;
  // Partitions (fnmatch patterns) it may publish in; empty: any. An agent-<id> gets only its
  // robot's partitions "smart.run.*.robot.<id>" (idl/smart.idl, "Runs"), so its key speaks for
  // its robot alone (issue 25).
  std::vector<std::string> publish_partitions;
};

std::string subject_of(const std::string& identity);  // "CN=<identity>,O=SMART-DDS"
std::vector<Grant> role_grants(const std::vector<uint32_t>& agent_ids);
std::string governance_xml();
// not_before / not_after: "YYYY-MM-DDTHH:MM:SS" (UTC).
std::string permissions_xml(const Grant& grant, const std::string& not_before,
                            const std::string& not_after);

// Writes the keystore (see above); throws std::runtime_error naming the openssl step that failed.
void init_keystore(const std::filesystem::path& dir, const std::vector<uint32_t>& agent_ids,
                   int valid_days);

// The files of `identity` in keystore `dir`; throws config::ConfigError naming the missing file
// and how to make it.
dds::SecurityFiles identity_files(const std::filesystem::path& dir, const std::string& identity);

}  // namespace smart::security
