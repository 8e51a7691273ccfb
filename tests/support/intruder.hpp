// An intruder that reads the protocol (issue 25): a DDS participant in the "smart.run.*" wildcard
// partition, so every run's readers hear it, or in one run's exact partition (learned from
// discovery), whose writers take the highest ownership strength there is (2^31-1), with a spy
// that learns the run id from the monitor's action windows. What it sends is up to the test: a
// loop calls `act` every 10 ms on its own thread until the intruder is destroyed.
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <string>
#include <thread>

#include "smart/dds/wire.hpp"
#include "support/dds_test_support.hpp"

namespace smart::test {

class Intruder {
 public:
  static constexpr int32_t kStrongest = 2147483647;
  // Several intruders of one test share its domain (a process has each domain once).
  explicit Intruder(const dds::Domain& domain, const std::string& run = "*")
      : domain_(domain), p_(domain_, run), qos_(dds::find_qos_profile("lan")), spy_(p_, qos_) {}
  ~Intruder() { stop(); }

  // Its writers: dds::WireWriter<T> w(intruder.participant(), intruder.qos(), kStrongest).
  const dds::Participant& participant() const { return p_; }
  const dds::QosProfile& qos() const { return qos_; }
  // The run id the monitor's windows carry (0 until one came); call from `act` or after start.
  uint64_t run_id() {
    spy_.take_each([&](const smart_msg_ActionWindow& w) { run_ = w.run_id; });
    return run_;
  }
  void start(std::function<void(Intruder&)> act) {
    act_ = std::move(act);
    thread_ = std::thread([this] {
      while (!done_) {
        act_(*this);
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    });
  }
  void stop() {
    done_ = true;
    if (thread_.joinable()) thread_.join();
  }

 private:
  dds::Domain domain_;
  dds::Participant p_;
  dds::QosProfile qos_;
  dds::WireReader<smart_msg_ActionWindow> spy_;
  uint64_t run_ = 0;
  std::function<void(Intruder&)> act_;
  std::thread thread_;
  std::atomic<bool> done_{false};
};

}  // namespace smart::test
