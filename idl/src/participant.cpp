#include "smart/dds/participant.hpp"

#include <string>

#include "smart/dds/error.hpp"

namespace smart::dds {

namespace {
// With DDS Security on, a refused participant almost always means a bad keystore, not a network
// problem: say so, naming the identity.
std::string what_failed(const Domain& domain) {
  std::string what = "creating a participant in domain " + std::to_string(domain.id());
  if (const auto& s = domain.config().security) {
    what += " with DDS Security (identity " + s->identity_certificate +
            "): the keystore's certificates, governance or permissions were refused; make it "
            "again with `smart security init`, check the dates, and use one keystore for every "
            "process of the run";
  }
  return what;
}
}  // namespace

Participant::Participant(const Domain& domain, std::string run)
    : domain_(domain),
      entity_(check(dds_create_participant(domain.id(), nullptr, nullptr), what_failed(domain))),
      run_(std::move(run)) {}

}  // namespace smart::dds
