#include "ownership_edge.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <random>
#include <thread>

#include "smart/dds/participant_directory.hpp"

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
    : run_name_(p.run()),
      partition_(p.run_partition()),
      domain_id_(static_cast<int>(p.domain_id())),
      out_(p, qos),
      from_monitors_(dds::admit_roles(p, {"monitor"})),
      in_(p, qos, from_monitors_) {
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
  std::snprintf(m.run, sizeof(m.run), "%s", run_name_.c_str());
  m.pid = self_.pid;
  m.strength = self_.strength;
  m.resume = resume;
  out_.write(m);
  announcement_ = m;
  t0_ = announced_ = std::chrono::steady_clock::now();
}

double MonitorAnnouncer::now_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
}

void MonitorAnnouncer::read_claims(double now_s) {
  for (const auto& [writer, n] : from_monitors_.take_refused()) {
    if (rejected_.count("monitor", dds::kNotRunMember, {}, n)) {
      spdlog::warn("monitor: {} announcement(s) on run '{}' from {} ignored: {}", n, run_name_,
                   describe_sender(in_.participant_of(writer)), dds::kNotRunMember);
    }
  }
  for (;;) {
    auto samples = in_.take();
    if (samples.empty()) return;
    for (auto s : samples) {
      const auto& m = s.data();  // key fields are set in invalid samples too
      if (!s.alive()) {
        claims_.gone(m.monitor_id);
      } else if (s.valid() && m.monitor_id != self_.monitor_id) {
        take_claim(m, s.info().publication_handle, now_s);
      }
    }
  }
}

void MonitorAnnouncer::take_claim(const smart_msg_MonitorInfo& m, dds_instance_handle_t from,
                                  double now_s) {
  auto why = wire::check_monitor_info(m);
  const auto parts = in_.partitions_of(from);
  if (why.empty() && parts && *parts != std::vector<std::string>{partition_}) {
    why = "written to partitions other than exactly this run's '" + partition_ +
          "' (a wildcard reaches every run)";
  }
  if (why.empty()) return claims_.heard(claim_of(m), now_s);
  if (rejected_.count("monitor", why)) {
    spdlog::warn("monitor: announcement on run '{}' from {} ignored: {}", run_name_,
                 describe_sender(in_.participant_of(from)), why);
  }
}

std::optional<std::string> MonitorAnnouncer::poll() {
  // Written again each second: the same claim (keep-last), this monitor's sign of life, whose
  // fresh source timestamps also let `smart doctor` on any host measure this host's clock offset.
  if (const auto now = std::chrono::steady_clock::now();
      now - announced_ >= std::chrono::seconds(1)) {
    out_.write(announcement_);
    announced_ = now;
  }
  const double now = now_s();
  read_claims(now);
  const auto others = claims_.live(now);
  for (const auto& c : others) {
    if ((owned_ || wire::outranks(self_, c)) && warned_.insert(c.monitor_id).second) {
      spdlog::warn(
          "monitor: a second {} joined run '{}'; it is refused, this monitor keeps the "
          "fleet",
          wire::describe(c), run_name_);
    }
  }
  const auto owner = owned_ ? std::nullopt : wire::owner_over(self_, others);
  if (!owner) return std::nullopt;
  return "refused: run '" + run_name_ + "' on domain " + std::to_string(domain_id_) +
         " is already owned by the " + wire::describe(*owner) +
         (self_.resume ? ", which is alive; --resume takes over only a run whose monitor stopped"
                       : "; stop that monitor, start this one with another --run, or take the "
                         "run over with --resume once it has stopped");
}

std::optional<std::string> MonitorAnnouncer::settle(const std::function<bool()>& hosts_matched,
                                                    double max_s) {
  // Discovery of another monitor takes about as long as that of the hosts: once a host is
  // matched, a short grace suffices; a claim heard once is waited for until it repeats or is
  // known to be stale (wire::kClaimLiveS).
  double matched_at = -1;
  for (;;) {
    if (auto refusal = poll()) return refusal;
    const double t = now_s();
    if (matched_at < 0 && hosts_matched()) matched_at = t;
    const bool discovered = t >= max_s || (matched_at >= 0 && t - matched_at > 0.2);
    if (discovered && !claims_.pending(t)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return poll();
}

std::string describe_sender(const std::optional<dds_guid_t>& participant) {
  return dds::describe_sender(participant);
}

bool same_guid(const dds_guid_t& a, const dds_guid_t& b) {
  return std::memcmp(a.v, b.v, sizeof(a.v)) == 0;
}

}  // namespace smart::monitor
