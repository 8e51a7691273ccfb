// Contract: a Participant is one process's membership in a Domain; it keeps the Domain alive.
// Move-only. Topics, writers, readers and wait sets are created from it.
#pragma once

#include <dds/dds.h>

#include "smart/dds/domain.hpp"
#include "smart/dds/entity.hpp"

namespace smart::dds {

class Participant {
 public:
  explicit Participant(const Domain& domain);
  dds_entity_t handle() const { return entity_.handle(); }
  dds_domainid_t domain_id() const { return domain_.id(); }
  const Domain& domain() const { return domain_; }

 private:
  Domain domain_;  // shared handle: declared first so it is destroyed after the participant
  Entity entity_;
};

}  // namespace smart::dds
