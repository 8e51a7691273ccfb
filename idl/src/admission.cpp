#include "smart/dds/admission.hpp"

namespace smart::dds {

void WriterAdmission::admit(dds_instance_handle_t writer) {
  std::lock_guard lock(mutex_);
  admitted_.insert(writer);
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

bool WriterAdmission::hear(dds_instance_handle_t writer) {
  std::lock_guard lock(mutex_);
  if (!closed_ || admitted_.count(writer)) return true;
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

}  // namespace smart::dds
