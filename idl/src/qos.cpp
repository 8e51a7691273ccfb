#include "smart/dds/qos.hpp"

#include <utility>

#include "smart/dds/error.hpp"

namespace smart::dds {

std::string to_string(Reliability r) {
  return r == Reliability::kReliable ? "reliable" : "best_effort";
}
std::string to_string(Durability d) {
  return d == Durability::kTransientLocal ? "transient_local" : "volatile";
}
std::string to_string(HistoryKind h) {
  return h == HistoryKind::kKeepAll ? "keep_all" : "keep_last";
}
std::string to_string(LivelinessKind l) {
  switch (l) {
    case LivelinessKind::kAutomatic:
      return "automatic";
    case LivelinessKind::kManualByParticipant:
      return "manual_by_participant";
    case LivelinessKind::kManualByTopic:
      return "manual_by_topic";
  }
  return "automatic";
}

dds_duration_t to_dds_duration(Millis ms) { return DDS_MSECS(ms.count()); }

Qos::Qos() : qos_(dds_create_qos()) {
  if (qos_ == nullptr) throw Error(DDS_RETCODE_OUT_OF_RESOURCES, "dds_create_qos");
}
Qos::Qos(const Qos& other) : Qos() { check(dds_copy_qos(qos_, other.qos_), "dds_copy_qos"); }
Qos& Qos::operator=(const Qos& other) {
  if (this != &other) check(dds_copy_qos(qos_, other.qos_), "dds_copy_qos");
  return *this;
}
Qos::Qos(Qos&& other) noexcept : qos_(std::exchange(other.qos_, nullptr)) {}
Qos& Qos::operator=(Qos&& other) noexcept {
  std::swap(qos_, other.qos_);
  return *this;
}
Qos::~Qos() {
  if (qos_ != nullptr) dds_delete_qos(qos_);
}

Qos& Qos::reliability(Reliability r, Millis max_blocking) {
  dds_qset_reliability(
      qos_, r == Reliability::kReliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT,
      to_dds_duration(max_blocking));
  return *this;
}
Qos& Qos::durability(Durability d) {
  dds_qset_durability(qos_, d == Durability::kTransientLocal ? DDS_DURABILITY_TRANSIENT_LOCAL
                                                             : DDS_DURABILITY_VOLATILE);
  return *this;
}
Qos& Qos::keep_last(int32_t depth) {
  dds_qset_history(qos_, DDS_HISTORY_KEEP_LAST, depth);
  return *this;
}
Qos& Qos::keep_all() {
  dds_qset_history(qos_, DDS_HISTORY_KEEP_ALL, DDS_LENGTH_UNLIMITED);
  return *this;
}
Qos& Qos::deadline(Millis period) {
  dds_qset_deadline(qos_, to_dds_duration(period));
  return *this;
}
Qos& Qos::lifespan(Millis duration) {
  dds_qset_lifespan(qos_, to_dds_duration(duration));
  return *this;
}
Qos& Qos::liveliness(LivelinessKind kind, Millis lease) {
  dds_liveliness_kind_t k = DDS_LIVELINESS_AUTOMATIC;
  if (kind == LivelinessKind::kManualByParticipant) k = DDS_LIVELINESS_MANUAL_BY_PARTICIPANT;
  if (kind == LivelinessKind::kManualByTopic) k = DDS_LIVELINESS_MANUAL_BY_TOPIC;
  dds_qset_liveliness(qos_, k, to_dds_duration(lease));
  return *this;
}
Qos& Qos::autodispose_unregistered(bool autodispose) {
  dds_qset_writer_data_lifecycle(qos_, autodispose);
  return *this;
}
Qos& Qos::exclusive_ownership(int32_t strength) {
  dds_qset_ownership(qos_, DDS_OWNERSHIP_EXCLUSIVE);
  dds_qset_ownership_strength(qos_, strength);
  return *this;
}
Qos& Qos::partition(const std::string& name) {
  dds_qset_partition1(qos_, name.c_str());
  return *this;
}
Qos& Qos::partitions(const std::vector<std::string>& names) {
  std::vector<const char*> ps;
  ps.reserve(names.size());
  for (const auto& n : names) ps.push_back(n.c_str());
  dds_qset_partition(qos_, static_cast<uint32_t>(ps.size()), ps.data());
  return *this;
}
Qos& Qos::user_data(const std::string& data) {
  dds_qset_userdata(qos_, data.data(), data.size());
  return *this;
}
Qos& Qos::resource_limits(int32_t max_samples, int32_t max_instances, int32_t max_per_instance) {
  dds_qset_resource_limits(qos_, max_samples, max_instances, max_per_instance);
  return *this;
}

Qos TopicQos::to_dds() const {
  Qos q;
  q.reliability(reliability, max_blocking).durability(durability);
  if (history == HistoryKind::kKeepAll) {
    q.keep_all();
  } else {
    q.keep_last(depth);
  }
  if (deadline) q.deadline(*deadline);
  if (lifespan) q.lifespan(*lifespan);
  if (liveliness_lease) q.liveliness(liveliness, *liveliness_lease);
  q.autodispose_unregistered(autodispose);
  return q;
}

}  // namespace smart::dds
