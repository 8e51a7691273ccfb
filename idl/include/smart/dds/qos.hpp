// Contract: TopicQos is a plain value describing the QoS policies SMART-DDS uses (reliability,
// history, durability, deadline, liveliness, lifespan, writer-data-lifecycle); to_dds() renders it
// into an owned Qos object. Qos owns a dds_qos_t and is movable and copyable.
#pragma once

#include <dds/dds.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace smart::dds {

using Millis = std::chrono::milliseconds;

enum class Reliability { kBestEffort, kReliable };
enum class Durability { kVolatile, kTransientLocal };
enum class HistoryKind { kKeepLast, kKeepAll };
enum class LivelinessKind { kAutomatic, kManualByParticipant, kManualByTopic };

std::string to_string(Reliability r);
std::string to_string(Durability d);
std::string to_string(HistoryKind h);
std::string to_string(LivelinessKind l);

dds_duration_t to_dds_duration(Millis ms);

class Qos {
 public:
  Qos();
  Qos(const Qos& other);
  Qos& operator=(const Qos& other);
  Qos(Qos&& other) noexcept;
  Qos& operator=(Qos&& other) noexcept;
  ~Qos();

  Qos& reliability(Reliability r, Millis max_blocking = Millis(100));
  Qos& durability(Durability d);
  Qos& keep_last(int32_t depth);
  Qos& keep_all();
  Qos& deadline(Millis period);
  Qos& lifespan(Millis duration);
  Qos& liveliness(LivelinessKind kind, Millis lease);
  Qos& autodispose_unregistered(bool autodispose);
  // Exclusive ownership (readers take an instance from its strongest live writer only) with
  // this writer's strength; shared ownership is the default.
  Qos& exclusive_ownership(int32_t strength);
  // The one partition this reader or writer is in (on a reader/writer made directly on the
  // participant, Cyclone applies it to the implicit publisher/subscriber).
  Qos& partition(const std::string& name);
  Qos& partitions(const std::vector<std::string>& names);
  // USER_DATA (DDS 1.4, 2.2.3.1): opaque bytes discovery delivers with the endpoint (a writer's
  // run proof, smart/wire/run_proof.hpp).
  Qos& user_data(const std::string& data);
  // Resource limits bound the reader/writer cache when keep_all is used.
  Qos& resource_limits(int32_t max_samples, int32_t max_instances, int32_t max_per_instance);

  const dds_qos_t* get() const { return qos_; }
  dds_qos_t* get() { return qos_; }

 private:
  dds_qos_t* qos_;
};

struct TopicQos {
  Reliability reliability = Reliability::kReliable;
  Millis max_blocking{100};
  HistoryKind history = HistoryKind::kKeepLast;
  int32_t depth = 1;
  Durability durability = Durability::kVolatile;
  std::optional<Millis> deadline;
  std::optional<Millis> lifespan;
  LivelinessKind liveliness = LivelinessKind::kAutomatic;
  std::optional<Millis> liveliness_lease;
  bool autodispose = true;

  Qos to_dds() const;
  bool operator==(const TopicQos&) const = default;
};

}  // namespace smart::dds
