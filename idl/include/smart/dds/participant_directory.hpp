// Contract: who a remote participant is, from DDS discovery (the DCPSParticipant builtin topic):
// Cyclone DDS announces each participant's host name, pid and process name as properties
// (__Hostname, __Pid, __ProcessName; dds/ddsi/q_protocol.h). Used to name the sender of
// refused samples (issue 25: the summary names suspected intruders). A remote program may lie in
// these properties: they are a hint for a person, never a credential.
#pragma once

#include <dds/dds.h>

#include <optional>
#include <string>

#include "smart/dds/entity.hpp"
#include "smart/dds/participant.hpp"

namespace smart::dds {

// "0110a2b3:c4d5e6f7:01020304" (the GUID prefix: the host and process that sent a sample).
std::string guid_prefix(const dds_guid_t& guid);
// "participant <guid_prefix>" for a matched writer's participant, or "a writer that left".
std::string describe_sender(const std::optional<dds_guid_t>& participant);

class ParticipantDirectory {
 public:
  explicit ParticipantDirectory(const Participant& p);
  // "participant 0110a2b3:...:01020304 (host h, pid 12, smart)", without the parenthesis when
  // discovery did not say; "a writer that left" for no participant.
  std::string describe(const std::optional<dds_guid_t>& participant) const;

 private:
  Entity reader_;
};

}  // namespace smart::dds
