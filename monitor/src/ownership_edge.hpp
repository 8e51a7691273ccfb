// The monitor's side of run ownership (idl/smart.idl, "Ownership"), at the DDS edge:
// - MonitorAnnouncer: announces this monitor on the run's MonitorInfo topic (kept while it
//   lives; again each second from poll(), for other hosts' clock checks and as its sign of
//   life) and watches the others; poll() returns why this monitor must give way, naming the
//   live monitor that owns the run (wire/ownership.hpp decides), or nothing. Announcements
//   from a writer outside exactly this run's partition (the "smart.run.*" wildcard reaches
//   every run) are refused, and a claim counts only once repeated (wire::ClaimBook); with a run
//   key only monitors proven with it are heard (--resume needs the run's key).
// - SenderGate: who may report what: progress for a robot only from the writer that first
//   reported it (until that writer leaves: a restarted host takes over, and its newest refused
//   sample is taken then, as its progress is cumulative), clock ticks only from
//   one sim host, its status only from that same participant.
#pragma once

#include <dds/dds.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "smart/convert/validate.hpp"
#include "smart/dds/wire.hpp"
#include "smart/wire/ownership.hpp"

namespace smart::monitor {

// "participant 0110a2b3:..." (its GUID prefix: the host and process that sent a sample), or
// "a writer that left" when it is no longer matched.
std::string describe_sender(const std::optional<dds_guid_t>& participant);

class MonitorAnnouncer {
 public:
  MonitorAnnouncer(const dds::Participant& p, const dds::QosProfile& qos, uint64_t run_id,
                   bool resume);
  int32_t strength() const { return self_.strength; }
  // A refusal naming the owner, or nothing; logs (once per monitor) monitors this one outranks.
  // Once this monitor owns the run (owned()), it never refuses: a later claim is logged only.
  std::optional<std::string> poll();
  // Before start(): give another monitor of the run time to be discovered and a claim heard
  // once time to repeat (up to max, less once hosts are matched); returns poll()'s verdict.
  std::optional<std::string> settle(const std::function<bool()>& hosts_matched, double max_s);
  void owned() { owned_ = true; }

 private:
  void read_claims(double now_s);
  void take_claim(const smart_msg_MonitorInfo& m, dds_instance_handle_t from, double now_s);
  double now_s() const;

  wire::MonitorClaim self_;
  std::string run_name_;
  std::string partition_;
  int domain_id_;
  dds::WireWriter<smart_msg_MonitorInfo> out_;
  dds::WriterAdmission from_monitors_;  // before in_: with a run key, proven monitors only
  dds::WireReader<smart_msg_MonitorInfo> in_;
  wire::ClaimBook claims_;
  std::set<uint64_t> warned_;
  wire::Rejections rejected_;  // announcements that fail wire::check_monitor_info
  smart_msg_MonitorInfo announcement_{};
  std::chrono::steady_clock::time_point t0_, announced_;
  bool owned_ = false;
};

bool same_guid(const dds_guid_t& a, const dds_guid_t& b);

class SenderGate {
 public:
  explicit SenderGate(std::size_t robots) : progress_holder_(robots, 0), held_back_(robots) {}
  // Each returns why the sample is refused, or an empty string. `matched` says whether a writer
  // (publication handle) is still matched; `participant` gives a writer's participant.
  template <class Reader>
  std::string progress(const smart_msg_Progress& sample, dds_instance_handle_t from,
                       const Reader& reader) {
    const uint32_t robot = sample.robot_id;
    auto& holder = progress_holder_[robot];
    if (holder == from) return {};
    if (!reader.writer_at_least(from, dds::kHostStrength)) return kWeakWriter;
    if (holder != 0 && reader.writer_matched(holder)) {
      held_back_[robot] = {from, sample};
      return "robot " + std::to_string(robot) +
             " is held by another host's writer in this run; progress from a second writer "
             "is refused";
    }
    holder = from;
    held_back_[robot].reset();
    return {};
  }
  // Newest refused progress of writers whose robot's holder has left since: fn(sample).
  template <class Reader, class Fn>
  void release_held_back(const Reader& reader, Fn&& fn) {
    for (std::size_t r = 0; r < held_back_.size(); ++r) {
      if (!held_back_[r] || reader.writer_matched(progress_holder_[r])) continue;
      const auto [from, sample] = *held_back_[r];
      held_back_[r].reset();
      if (reader.writer_matched(from)) {
        progress_holder_[r] = from;
        fn(sample);
      }
    }
  }
  template <class Reader>
  std::string clock(dds_instance_handle_t from, const Reader& reader) {
    if (sim_clock_ == from) return {};
    if (!reader.writer_at_least(from, dds::kHostStrength)) return kWeakWriter;
    if (sim_clock_ != 0 && reader.writer_matched(sim_clock_)) {
      return "clock ticks from a second sim host; this run follows the first";
    }
    sim_clock_ = from;
    sim_participant_ = reader.participant_of(from);
    return {};
  }
  // Before the sim host's first tick its status cannot be placed: keep it until then.
  bool sim_known() const { return sim_participant_.has_value(); }
  template <class Reader>
  bool sim_clock_matched(const Reader& reader) const {
    return sim_clock_ != 0 && reader.writer_matched(sim_clock_);
  }
  // The writer belongs to the sim host's participant (once known).
  template <class Reader>
  bool from_sim(dds_instance_handle_t writer, const Reader& reader) const {
    const auto who = reader.participant_of(writer);
    return sim_participant_ && who && same_guid(*who, *sim_participant_);
  }
  // The sim host's final status is often read after it left, and in a short run it may be its
  // first status sample: every status writer's participant is remembered while it is matched
  // (call when the matched count changed), and from earlier samples.
  template <class Reader>
  void remember_status_writers(const Reader& reader) {
    for (const auto h : reader.matched_writers()) {
      if (status_writers_.count(h)) continue;
      if (auto who = reader.participant_of(h)) status_writers_[h] = *who;
    }
  }
  template <class Reader>
  std::string status(dds_instance_handle_t from, const Reader& reader) {
    auto who = reader.participant_of(from);
    if (who) {
      status_writers_[from] = *who;
    } else if (auto it = status_writers_.find(from); it != status_writers_.end()) {
      who = it->second;
    }
    if (!sim_participant_ || !who || !same_guid(*who, *sim_participant_)) {
      return "sim status from a participant that is not this run's sim host";
    }
    return {};
  }

 private:
  static constexpr const char* kWeakWriter =
      "from a writer weaker than a SMART host's (not a sim host or agent of this version)";
  std::vector<dds_instance_handle_t> progress_holder_;
  std::vector<std::optional<std::pair<dds_instance_handle_t, smart_msg_Progress>>> held_back_;
  dds_instance_handle_t sim_clock_ = 0;
  std::optional<dds_guid_t> sim_participant_;
  std::map<dds_instance_handle_t, dds_guid_t> status_writers_;
};

// A reader bound to the run's sim host once the gate knows it (its first tick; with a run key
// only proven sim hosts are heard at all, so that first tick is a sim host's): from then on
// Cyclone hands it only the samples of that participant's writers, and of this process's own
// (dds::WriterAdmission, inside the receive path), so no stronger or flooding stranger can hide
// or delay them (issue 25: a tick from a second sim silenced the real one). refresh() each
// turn: cheap unless a writer matched or the sim host just became known.
template <class T>
class SimBoundReader {
 public:
  SimBoundReader(const dds::Participant& p, const dds::QosProfile& qos)
      : admission_(dds::admit_roles(p, {"sim"})), reader_(p, qos, admission_) {
    dds_get_guid(p.handle(), &self_);
  }
  dds::WireReader<T>& reader() { return reader_; }
  const dds::WireReader<T>& reader() const { return reader_; }
  // Admits the sim host's writers when due (the sim host just became known, or a writer matched).
  void admit(const SenderGate& gate) {
    const auto matched = reader_.subscription_matched().total_count;
    if (!gate.sim_known() || (matched == matched_seen_ && admission_.closed())) return;
    matched_seen_ = matched;
    for (const auto h : reader_.matched_writers()) {
      const auto who = reader_.participant_of(h);
      if (gate.from_sim(h, reader_) || (who && same_guid(*who, self_))) admission_.admit(h);
    }
    admission_.close();
  }
  // admit(), then refused(writer, samples) for what was filtered out since the last call.
  template <class Fn>
  void refresh(const SenderGate& gate, Fn&& refused) {
    admit(gate);
    for (const auto& [writer, n] : admission_.take_refused()) refused(writer, n);
  }

 private:
  dds::WriterAdmission admission_;  // before the reader: its filter points here
  dds::WireReader<T> reader_;
  dds_guid_t self_{};
  uint32_t matched_seen_ = 0;
};

}  // namespace smart::monitor
