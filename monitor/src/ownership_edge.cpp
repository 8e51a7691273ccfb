#include "ownership_edge.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <random>
#include <thread>

namespace smart::monitor {

namespace {
uint64_t unix_time_ms() {
  return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::milliseconds>(
                                   std::chrono::system_clock::now().time_since_epoch())
                                   .count());
}

std::string host_name() {
  char name[65] = {};
  if (gethostname(name, sizeof(name) - 1) != 0) return "?";
  return name;
}

wire::MonitorClaim claim_of(const smart_msg_MonitorInfo& m) {
  return {m.monitor_id, m.run_id, m.host, m.pid, m.strength, m.resume};
}
}  // namespace

MonitorAnnouncer::MonitorAnnouncer(const dds::Participant& p, const dds::QosProfile& qos,
                                   uint64_t run_id, bool resume)
    : run_name_(p.run()), domain_id_(static_cast<int>(p.domain_id())), out_(p, qos), in_(p, qos) {
  std::random_device rd;
  self_ = {(uint64_t{rd()} << 32) | rd(),
           run_id,
           host_name().substr(0, 64),
           static_cast<int32_t>(getpid()),
           wire::monitor_strength(unix_time_ms(), resume),
           resume};
  smart_msg_MonitorInfo m{};
  m.monitor_id = self_.monitor_id;
  m.run_id = run_id;
  std::snprintf(m.host, sizeof(m.host), "%s", self_.host.c_str());
  m.pid = self_.pid;
  m.strength = self_.strength;
  m.resume = resume;
  out_.write(m);
  announcement_ = m;
  announced_ = std::chrono::steady_clock::now();
}

std::optional<std::string> MonitorAnnouncer::poll() {
  // Written again each second: the same claim (keep-last), whose fresh source timestamps let
  // `smart doctor` on any host measure this host's clock offset.
  if (const auto now = std::chrono::steady_clock::now();
      now - announced_ >= std::chrono::seconds(1)) {
    out_.write(announcement_);
    announced_ = now;
  }
  for (auto s : in_.take()) {
    const auto& m = s.data();  // key fields are set in invalid samples too
    if (!s.alive()) {
      others_.erase(m.monitor_id);
    } else if (s.valid() && m.monitor_id != self_.monitor_id) {
      if (auto why = wire::check_monitor_info(m); !why.empty()) {
        if (rejected_.count("monitor", why)) {
          spdlog::warn("monitor: announcement on run '{}' rejected: {}", run_name_, why);
        }
        continue;
      }
      others_[m.monitor_id] = claim_of(m);
    }
  }
  std::vector<wire::MonitorClaim> others;
  for (const auto& [id, c] : others_) {
    others.push_back(c);
    if (wire::outranks(self_, c) && warned_.insert(id).second) {
      spdlog::warn(
          "monitor: a second {} joined run '{}'; it is refused, this monitor keeps the "
          "fleet",
          wire::describe(c), run_name_);
    }
  }
  const auto owner = wire::owner_over(self_, others);
  if (!owner) return std::nullopt;
  return "refused: run '" + run_name_ + "' on domain " + std::to_string(domain_id_) +
         " is already owned by the " + wire::describe(*owner) +
         "; stop that monitor, start this one with another --run, or take the run over with "
         "--resume";
}

std::optional<std::string> MonitorAnnouncer::settle(const std::function<bool()>& hosts_matched,
                                                    double max_s) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  auto since = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  // Discovery of another monitor takes about as long as that of the hosts: once a host is
  // matched, a short grace suffices.
  double matched_at = -1;
  while (since() < max_s) {
    if (auto refusal = poll()) return refusal;
    if (matched_at < 0 && hosts_matched()) matched_at = since();
    if (matched_at >= 0 && since() - matched_at > 0.2) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return poll();
}

std::string describe_sender(const std::optional<dds_guid_t>& participant) {
  if (!participant) return "a writer that left";
  std::string out = "participant ";
  char hex[3];
  for (std::size_t i = 0; i < 12; ++i) {  // the GUID prefix; the rest names the entity
    std::snprintf(hex, sizeof(hex), "%02x", participant->v[i]);
    out += hex;
    if (i % 4 == 3 && i < 11) out += ':';
  }
  return out;
}

bool SenderGate::same(const dds_guid_t& a, const dds_guid_t& b) {
  return std::memcmp(a.v, b.v, sizeof(a.v)) == 0;
}

}  // namespace smart::monitor
