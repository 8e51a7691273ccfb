#include "smart/dds/participant.hpp"

#include <string>

#include "smart/dds/error.hpp"

namespace smart::dds {

Participant::Participant(const Domain& domain, std::string run)
    : domain_(domain),
      entity_(check(dds_create_participant(domain.id(), nullptr, nullptr),
                    "creating a participant in domain " + std::to_string(domain.id()))),
      run_(std::move(run)) {}

}  // namespace smart::dds
