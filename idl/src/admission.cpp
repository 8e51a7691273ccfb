#include "smart/dds/admission.hpp"

#include <algorithm>
#include <cstring>
#include <string>
#include <utility>

namespace smart::dds {

namespace {
std::string user_data_of(const dds_qos_t* qos) {
  void* data = nullptr;
  size_t size = 0;
  if (qos == nullptr || !dds_qget_userdata(qos, &data, &size)) return {};
  std::string out(static_cast<const char*>(data), size);
  dds_free(data);
  return out;
}
}  // namespace

AdmitRule admit_roles(const Participant& participant, std::vector<std::string> roles) {
  if (!participant.run_key()) return {};
  return [key = *participant.run_key(), run = participant.run(),
          roles = std::move(roles)](const dds_builtintopic_endpoint_t& writer) {
    wire::GuidPrefix prefix{};
    std::memcpy(prefix.data(), writer.participant_key.v, prefix.size());
    const auto role = wire::proven_role(key, user_data_of(writer.qos), run, prefix);
    if (!role) return Verdict::kRefuse;
    return std::find(roles.begin(), roles.end(), *role) != roles.end() ? Verdict::kAdmit
                                                                       : Verdict::kIgnore;
  };
}

WriterAdmission::WriterAdmission(AdmitRule rule)
    : rule_(std::move(rule)), closed_(rule_ != nullptr) {}

void WriterAdmission::admit(dds_instance_handle_t writer) {
  std::lock_guard lock(mutex_);
  admitted_.insert(writer);
  ignored_.erase(writer);
}

void WriterAdmission::close() {
  std::lock_guard lock(mutex_);
  closed_ = true;
}

bool WriterAdmission::closed() const {
  std::lock_guard lock(mutex_);
  return closed_;
}

bool WriterAdmission::admitted(dds_instance_handle_t writer) const {
  std::lock_guard lock(mutex_);
  return admitted_.count(writer) > 0;
}

void WriterAdmission::decide(dds_entity_t reader, dds_instance_handle_t writer) {
  if (!rule_ || writer == 0) return;
  {
    std::lock_guard lock(mutex_);
    if (admitted_.count(writer) || ignored_.count(writer)) return;
  }
  dds_builtintopic_endpoint_t* e = dds_get_matched_publication_data(reader, writer);
  if (e == nullptr) return;  // left already, or the reader is still being made (decide_matched)
  const Verdict v = rule_(*e);
  dds_builtintopic_free_endpoint(e);
  std::lock_guard lock(mutex_);
  if (v == Verdict::kAdmit) admitted_.insert(writer);
  if (v == Verdict::kIgnore) ignored_.insert(writer);
}

void WriterAdmission::decide_matched(dds_entity_t reader) {
  if (!rule_) return;
  std::vector<dds_instance_handle_t> handles(64);
  for (;;) {
    const auto n = dds_get_matched_publications(reader, handles.data(), handles.size());
    if (n < 0) return;
    if (static_cast<std::size_t>(n) <= handles.size()) {
      handles.resize(static_cast<std::size_t>(n));
      break;
    }
    handles.resize(static_cast<std::size_t>(n));
  }
  for (const auto h : handles) decide(reader, h);
}

bool WriterAdmission::hear(dds_instance_handle_t writer) {
  std::lock_guard lock(mutex_);
  if (!closed_ || admitted_.count(writer)) return true;
  if (ignored_.count(writer)) return false;
  const bool known = refused_.count(writer) > 0;
  ++refused_[known || refused_.size() < kMaxWriters ? writer : 0];
  return false;
}

std::map<dds_instance_handle_t, uint64_t> WriterAdmission::take_refused() {
  std::lock_guard lock(mutex_);
  std::map<dds_instance_handle_t, uint64_t> out;
  out.swap(refused_);
  return out;
}

bool WriterAdmission::filter(const dds_sample_info_t* info, void* self) {
  // Sample info is all zero when filtering a write on this topic: no writer of ours uses it.
  return static_cast<WriterAdmission*>(self)->hear(info->publication_handle);
}

void WriterAdmission::on_matched(dds_entity_t reader, dds_subscription_matched_status_t status,
                                 void* self) {
  static_cast<WriterAdmission*>(self)->decide(reader, status.last_publication_handle);
}

}  // namespace smart::dds
