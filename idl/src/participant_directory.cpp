#include "smart/dds/participant_directory.hpp"

#include <dds/ddsi/q_protocol.h>

#include <cstdio>
#include <cstring>
#include <vector>

#include "smart/dds/error.hpp"

namespace smart::dds {

std::string guid_prefix(const dds_guid_t& guid) {
  std::string out;
  char hex[3];
  for (std::size_t i = 0; i < 12; ++i) {  // the prefix; the rest names the entity
    std::snprintf(hex, sizeof(hex), "%02x", guid.v[i]);
    out += hex;
    if (i % 4 == 3 && i < 11) out += ':';
  }
  return out;
}

std::string describe_sender(const std::optional<dds_guid_t>& participant) {
  return participant ? "participant " + guid_prefix(*participant) : "a writer that left";
}

ParticipantDirectory::ParticipantDirectory(const Participant& p)
    : reader_(
          check(dds_create_reader(p.handle(), DDS_BUILTIN_TOPIC_DCPSPARTICIPANT, nullptr, nullptr),
                "a reader of discovered participants")) {}

namespace {
// Printable ASCII only, at most 64 characters: it reaches logs and summary.json.
std::string property(const dds_qos_t* qos, const char* name) {
  char* value = nullptr;
  if (qos == nullptr || !dds_qget_prop(qos, name, &value) || value == nullptr) return {};
  std::string out;
  for (const char* c = value; *c != '\0' && out.size() < 64; ++c)
    out += (*c >= 32 && *c < 127) ? *c : '?';
  dds_free(value);
  return out;
}

std::string who(const dds_qos_t* qos) {
  const auto host = property(qos, DDS_BUILTIN_TOPIC_PARTICIPANT_PROPERTY_HOSTNAME);
  const auto pid = property(qos, DDS_BUILTIN_TOPIC_PARTICIPANT_PROPERTY_PID);
  const auto process = property(qos, DDS_BUILTIN_TOPIC_PARTICIPANT_PROPERTY_PROCESS_NAME);
  if (host.empty() && pid.empty() && process.empty()) return {};
  return " (host " + (host.empty() ? "?" : host) + ", pid " + (pid.empty() ? "?" : pid) +
         (process.empty() ? "" : ", " + process) + ")";
}
}  // namespace

std::string ParticipantDirectory::describe(const std::optional<dds_guid_t>& participant) const {
  if (!participant) return "a writer that left";
  std::string out = "participant " + guid_prefix(*participant);
  // Read, not take: every call sees the whole directory (one sample per participant); the
  // buffer grows until it holds them all.
  for (std::size_t size = 256;; size *= 4) {
    std::vector<void*> samples(size, nullptr);
    std::vector<dds_sample_info_t> infos(size);
    const int32_t n =
        dds_read(reader_.handle(), samples.data(), infos.data(), size, static_cast<uint32_t>(size));
    if (n <= 0) break;
    bool found = false;
    for (int32_t i = 0; i < n && !found; ++i) {
      const auto* p = static_cast<const dds_builtintopic_participant_t*>(samples[i]);
      found = infos[i].valid_data && std::memcmp(p->key.v, participant->v, 12) == 0;
      if (found) out += who(p->qos);
    }
    dds_return_loan(reader_.handle(), samples.data(), n);
    if (found || static_cast<std::size_t>(n) < size) break;
  }
  return out;
}

}  // namespace smart::dds
