// Contract: a reader that hears only admitted writers (issue 25: "a rejected sample must never
// hide an accepted one"). Cyclone DDS runs a topic filter with each arriving sample's info
// (dds.h, "Topic filters": publication_handle is its writer) before the sample enters the
// reader's history, so a sample from a writer that is not admitted can neither displace an
// admitted writer's sample from a keep-last history nor delay it. Open (every writer heard)
// until close(); from then on only the publication handles admit()ted. Refused samples are
// counted per writer (at most kMaxWriters writers; then under handle 0) for the edge to name.
// The filter runs on Cyclone's receive threads: the state is behind a mutex.
#pragma once

#include <dds/dds.h>

#include <cstdint>
#include <map>
#include <mutex>
#include <set>

namespace smart::dds {

class WriterAdmission {
 public:
  static constexpr std::size_t kMaxWriters = 64;
  WriterAdmission() = default;
  WriterAdmission(const WriterAdmission&) = delete;
  WriterAdmission& operator=(const WriterAdmission&) = delete;

  void admit(dds_instance_handle_t writer);
  void close();
  bool closed() const;
  bool admitted(dds_instance_handle_t writer) const;
  // The filter's decision for one sample (counted when refused).
  bool hear(dds_instance_handle_t writer);
  // Samples refused since the last call, by writer.
  std::map<dds_instance_handle_t, uint64_t> take_refused();
  // For dds_set_topic_filter_extended (arg: this).
  static bool filter(const dds_sample_info_t* info, void* self);

 private:
  mutable std::mutex mutex_;
  bool closed_ = false;
  std::set<dds_instance_handle_t> admitted_;
  std::map<dds_instance_handle_t, uint64_t> refused_;
};

}  // namespace smart::dds
