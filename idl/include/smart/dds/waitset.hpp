// Contract: WaitSet blocks a thread until one of its attached entities or conditions triggers
// (push, not poll). Attach a reader's data-available status, a ReadCondition or a
// GuardCondition; wait() returns the tags of the triggered attachments, empty on timeout.
#pragma once

#include <dds/dds.h>

#include <chrono>
#include <cstdint>
#include <vector>

#include "smart/dds/entity.hpp"
#include "smart/dds/participant.hpp"

namespace smart::dds {

// A condition the application triggers itself, e.g. to wake a waiting thread for shutdown.
class GuardCondition {
 public:
  explicit GuardCondition(const Participant& participant);
  void set(bool triggered);
  bool triggered() const;
  dds_entity_t handle() const { return entity_.handle(); }

 private:
  Entity entity_;
};

// Triggers while the reader holds samples in the given states (DDS_ANY_STATE by default).
class ReadCondition {
 public:
  explicit ReadCondition(dds_entity_t reader, uint32_t mask = DDS_ANY_STATE);
  dds_entity_t handle() const { return entity_.handle(); }

 private:
  Entity entity_;
};

class WaitSet {
 public:
  explicit WaitSet(const Participant& participant);
  // DDS_DATA_AVAILABLE_STATUS of a reader: the wait set wakes while the reader holds samples not
  // yet read or taken, through a ReadCondition of its own, so the reader's status mask is never
  // set. Cyclone 0.10's dds_set_status_mask holds the reader's lock while it waits for the
  // reader's running listeners, and the admission's listener calls into the reader
  // (admission.hpp): a monitor attaching its final wait set as the sim's writers left, or a sim
  // host attaching at start-up as the monitor's matched, hung for ever (CI, twice at stop 42).
  // Any other status (or entity) is enabled on the entity and attached as before.
  void attach_status(dds_entity_t entity, uint32_t status_mask, dds_attach_t tag);
  void attach(dds_entity_t condition, dds_attach_t tag);
  void detach(dds_entity_t entity_or_condition);
  std::vector<dds_attach_t> wait(std::chrono::milliseconds timeout);

 private:
  Entity entity_;
  std::vector<Entity> conditions_;  // read conditions made here; declared last: deleted first
};

}  // namespace smart::dds
