// Contract: the DDS edge of `smart serve --watch`: a read-only participant on the domain (no
// writer at all; under DDS Security the keystore's `viewer` identity, whose permissions allow
// subscribing only) that reads RobotState, Progress and MonitorInfo of every run (the run
// partitions by wildcard, idl/smart.idl "Runs") or of one named run, checks each sample
// (wire/validate.hpp; rejected ones are counted, never shown) and feeds a WatchBoard. A thread
// pumps samples until destruction; snapshot() may be called from any thread.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "smart/dds/domain.hpp"
#include "smart/dds/qos_profile.hpp"
#include "smart/serve/watch_board.hpp"

namespace smart::serve {

struct WatchOptions {
  int domain = 0;
  dds::DomainConfig config;  // network, security (the viewer identity)
  dds::QosProfile qos;
  std::string run;  // empty: every run on the domain
};

class FleetWatch {
 public:
  // Throws dds::Error when the participant or a reader cannot be made (names the domain).
  explicit FleetWatch(const WatchOptions& options);
  ~FleetWatch();
  nlohmann::json snapshot(uint64_t run_id = 0) const;

 private:
  struct Pump;
  void loop();
  std::unique_ptr<Pump> pump_;
  mutable std::mutex m_;
  WatchBoard board_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace smart::serve
