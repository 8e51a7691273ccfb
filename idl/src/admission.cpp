#include "smart/dds/admission.hpp"

#include <algorithm>
#include <cstring>
#include <string>
#include <utility>

namespace smart::dds {

std::string qos_user_data(const dds_qos_t* qos) {
  void* data = nullptr;
  size_t size = 0;
  if (qos == nullptr || !dds_qget_userdata(qos, &data, &size)) return {};
  std::string out(static_cast<const char*>(data), size);
  dds_free(data);
  return out;
}

std::vector<std::string> qos_partitions(const dds_qos_t* qos) {
  std::vector<std::string> out;
  uint32_t n = 0;
  char** ps = nullptr;
  if (qos != nullptr && dds_qget_partition(qos, &n, &ps)) {
    for (uint32_t i = 0; i < n; ++i) {
      out.emplace_back(ps[i]);
      dds_free(ps[i]);
    }
    dds_free(ps);
  }
  return out;
}

AdmitRule admit_roles(const Participant& participant, std::vector<std::string> roles) {
  if (!participant.run_key()) return {};
  return [key = *participant.run_key(), run = participant.run(),
          roles = std::move(roles)](const dds_builtintopic_endpoint_t& writer) {
    wire::GuidPrefix prefix{};
    std::memcpy(prefix.data(), writer.participant_key.v, prefix.size());
    const auto role = wire::proven_role(key, qos_user_data(writer.qos), run, prefix);
    if (!role) return Verdict::kRefuse;
    return std::find(roles.begin(), roles.end(), *role) != roles.end() ? Verdict::kAdmit
                                                                       : Verdict::kIgnore;
  };
}

WriterAdmission::WriterAdmission(AdmitRule rule)
    : rule_(std::move(rule)), closed_(rule_ != nullptr) {}

std::unique_ptr<WriterAdmission> WriterAdmission::per_robot(const Participant& participant,
                                                            std::vector<std::string> roles) {
  AdmitRule rule = admit_roles(participant, std::move(roles));
  if (!rule) rule = [](const dds_builtintopic_endpoint_t&) { return Verdict::kAdmit; };
  auto a = std::make_unique<WriterAdmission>(std::move(rule));
  a->run_partition_ = participant.run_partition();
  return a;
}

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
  // Read before the lookup: a lookup that fails while the reader is still being made (Cyclone
  // refuses a handle until dds_create_reader returns) says nothing about the writer, and a
  // forget() then could undo decide_matched()'s verdict, made meanwhile on the creating thread.
  const bool reader_made = reader_made_.load();
  dds_builtintopic_endpoint_t* e = dds_get_matched_publication_data(reader, writer);
  if (e == nullptr) {  // it left, or the reader is still being made (decide_matched follows)
    if (reader_made) forget(writer);
    return;
  }
  bool known = false;
  {
    std::lock_guard lock(mutex_);
    known = admitted_.count(writer) > 0 || ignored_.count(writer) > 0;
  }
  const Verdict v = known ? Verdict::kRefuse : rule_(*e);
  std::optional<Speaks> speaks;
  if (!known && v == Verdict::kAdmit && !run_partition_.empty()) {
    speaks = speaks_for(run_partition_, qos_partitions(e->qos));
  }
  dds_builtintopic_free_endpoint(e);
  if (known) return;
  std::lock_guard lock(mutex_);
  if (v == Verdict::kAdmit) admitted_.insert(writer);
  if (v == Verdict::kIgnore) ignored_.insert(writer);
  if (speaks) speaks_[writer] = *speaks;
}

void WriterAdmission::forget(dds_instance_handle_t writer) {
  std::lock_guard lock(mutex_);
  admitted_.erase(writer);
  ignored_.erase(writer);
  speaks_.erase(writer);
}

void WriterAdmission::decide_matched(dds_entity_t reader) {
  if (!rule_) return;
  reader_made_.store(true);
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

void WriterAdmission::count(std::map<dds_instance_handle_t, uint64_t>& m,
                            dds_instance_handle_t writer) {
  const bool known = m.count(writer) > 0;
  ++m[known || m.size() < kMaxWriters ? writer : 0];
}

bool WriterAdmission::hear(dds_instance_handle_t writer) {
  std::lock_guard lock(mutex_);
  if (!closed_ || admitted_.count(writer)) return true;
  if (ignored_.count(writer)) return false;
  count(refused_, writer);
  return false;
}

bool WriterAdmission::hear(dds_instance_handle_t writer, uint32_t robot) {
  std::lock_guard lock(mutex_);
  if (!closed_) return true;
  if (!admitted_.count(writer)) {
    if (!ignored_.count(writer)) count(refused_, writer);
    return false;
  }
  const auto it = speaks_.find(writer);
  if (it == speaks_.end() || may_speak(it->second, robot)) return true;
  count(misspoken_, writer);
  return false;
}

std::map<dds_instance_handle_t, uint64_t> WriterAdmission::take_refused() {
  std::lock_guard lock(mutex_);
  std::map<dds_instance_handle_t, uint64_t> out;
  out.swap(refused_);
  return out;
}

std::map<dds_instance_handle_t, uint64_t> WriterAdmission::take_misspoken() {
  std::lock_guard lock(mutex_);
  std::map<dds_instance_handle_t, uint64_t> out;
  out.swap(misspoken_);
  return out;
}

std::optional<Speaks> WriterAdmission::speaks(dds_instance_handle_t writer) const {
  std::lock_guard lock(mutex_);
  const auto it = speaks_.find(writer);
  return it == speaks_.end() ? std::nullopt : std::optional<Speaks>(it->second);
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
