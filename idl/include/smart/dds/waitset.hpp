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

// The one status a wait set waits on a reader for. Reader<T> enables it (and only it) when the
// reader is made, before its listener can run (reader.hpp says why that order matters).
inline constexpr uint32_t kReaderWaitStatus = DDS_DATA_AVAILABLE_STATUS;

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
  // For a reader or writer handle, also enables `status_mask` (e.g. DDS_DATA_AVAILABLE_STATUS)
  // unless exactly that is enabled already, as on every Reader<T> for kReaderWaitStatus: then the
  // reader is left alone, so attaching never waits for (or deadlocks with) its listeners.
  void attach_status(dds_entity_t entity, uint32_t status_mask, dds_attach_t tag);
  void attach(dds_entity_t condition, dds_attach_t tag);
  void detach(dds_entity_t entity_or_condition);
  std::vector<dds_attach_t> wait(std::chrono::milliseconds timeout);

 private:
  Entity entity_;
};

}  // namespace smart::dds
