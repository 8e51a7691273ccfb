#include "smart/dds/participant.hpp"

#include <cstring>
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

wire::GuidPrefix Participant::guid_prefix() const {
  dds_guid_t guid{};
  check(dds_get_guid(handle(), &guid), "reading the participant's GUID");
  wire::GuidPrefix prefix{};
  std::memcpy(prefix.data(), guid.v, prefix.size());
  return prefix;
}

void Participant::prove(const wire::RunKey& key, const std::string& role) {
  run_key_ = key;
  proof_ = wire::run_proof(key, role, run_, guid_prefix());
}

}  // namespace smart::dds
