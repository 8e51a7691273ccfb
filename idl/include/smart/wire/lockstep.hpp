// Contract: the lock-step handshake of idl/smart.idl (Clock), as pure state machines shared by
// the monitor and the sim host; no DDS, no clocks read, no threads (times are passed in).
//
// The sim host announces tick k after stepping, with sync_total = what it has reported (sum
// over robots of finished actions). The monitor answers tick k once it has taken exactly that
// much progress, with sync_total = what it has sent (sum over robots of the end of the windows
// it published). The host steps again only when its received windows add up to that. Counting,
// rather than trusting any order across topics, makes lock-step runs bit-identical.
//
// - SyncCounter: per-robot high-water marks and their sum (both sides count with it).
// - MonitorHandshake: keeps the newest announced tick; says when it may be answered, and when
//   to send the last answer again (a host that matched late missed it).
// - HostHandshake: waits for the answer to the tick it announced and the windows it announces;
//   says when to step, when to re-announce (a monitor that joined late missed the tick) and
//   when the monitor has been silent too long.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

namespace smart::wire {

// Start-up waits this many timeouts: a monitor for the sim it started, sim shards for each other
// (periods 0 and 1, sim/shard_barrier.hpp). Building a 1000-robot world or reading a large plan
// on a loaded machine can take longer than a running period ever should.
inline constexpr double kJoinTimeouts = 4;
// Start-up lasts until this tick is announced: tick 1 follows the sim's first step, which takes
// the run's first windows (and, sharded, the first hand-overs). The monitor and the sim shards
// both give it the join window, so neither gives up on the other sooner.
inline constexpr uint64_t kLastJoinTick = 1;

// One Clock sample of the handshake, either side.
struct Tick {
  uint64_t run_id = 0;
  uint64_t tick = 0;
  double sim_time_s = 0;
  uint64_t sync_total = 0;
  bool stop = false;
};

class SyncCounter {
 public:
  explicit SyncCounter(std::size_t robots = 0) : marks_(robots, 0) {}
  // Raises robot's mark to `mark` (never lowers it); returns by how much the total grew.
  uint64_t raise(uint32_t robot, uint64_t mark);
  uint64_t mark(uint32_t robot) const { return marks_[robot]; }
  uint64_t total() const { return total_; }
  std::size_t robots() const { return marks_.size(); }
  void reset();

 private:
  std::vector<uint64_t> marks_;
  uint64_t total_ = 0;
};

class MonitorHandshake {
 public:
  // A tick announced by the sim. Older than the last one answered: ignored (late, reordered).
  void on_tick(const Tick& announced);
  const std::optional<Tick>& pending() const { return pending_; }
  // The pending tick may be answered once the progress taken adds up to its sync_total.
  bool ready(uint64_t progress_taken) const {
    return pending_ && pending_->sync_total == progress_taken;
  }
  // The answer to the pending tick (which must be ready); clears it.
  Tick answer(uint64_t run_id, uint64_t windows_sent, bool stop);
  // The last tick answered (0 before any): where the final stop is sent.
  uint64_t last_answered() const { return last_answered_; }
  // The last answer went out (or out again) at now_s.
  void sent(double now_s) { sent_at_s_ = now_s; }
  // Send the last answer again: no newer tick for reanswer_s since it went out. The clock keeps
  // no history, so a host whose reader matched the monitor's writer after the answer went out
  // never gets it; a sim host announces its tick again (HostHandshake::should_reannounce), but
  // a sim shard other than the lead cannot (sim/shard_barrier.hpp): it waited, the lead waited
  // for its next exchange, and the run was lost as "the sim host went silent" at tick 0. The
  // repeat is the same sample: a host that has it, or has stepped past it, ignores it.
  bool should_reanswer(double now_s, double reanswer_s) const {
    return last_answer_ && !pending_ && now_s - sent_at_s_ > reanswer_s;
  }
  const std::optional<Tick>& last_answer() const { return last_answer_; }

 private:
  std::optional<Tick> pending_;
  std::optional<Tick> last_answer_;
  uint64_t last_answered_ = 0;
  bool answered_any_ = false;
  double sent_at_s_ = 0;
};

class HostHandshake {
 public:
  HostHandshake(double timeout_s, double reannounce_s)
      : timeout_s_(timeout_s), reannounce_s_(reannounce_s) {}
  // The host published `tick` at wall time now_s and now waits for its answer.
  void announced(uint64_t tick, double now_s);
  // The same tick published again (should_reannounce); the timeout still runs from announced().
  void reannounced(double now_s);
  // An answer of the monitor (the newest received). A stop is kept whatever its tick.
  void on_answer(const Tick& answer);
  bool stop() const { return stop_; }
  // The answer to the announced tick is in (a stop answering it too).
  bool answered() const { return answer_.has_value(); }
  // A stop is settled once the windows it counts (a stop answering our tick) are all received, so
  // the host's final states show every action the monitor sent (a lifelong run's last tick may
  // push windows with its stop).
  bool stop_settled(uint64_t windows_received) const {
    return stop_ && (!stop_total_ || windows_received >= *stop_total_);
  }
  // Step when the answer to our tick is in and the windows received add up to it.
  bool may_step(uint64_t run_id, uint64_t windows_received) const;
  // No answer yet and the last announcement is older than reannounce_s: announce again.
  bool should_reannounce(double now_s) const;
  // No answer for timeout_s since the tick was announced.
  bool timed_out(double now_s) const { return now_s - waiting_since_s_ > timeout_s_; }
  uint64_t tick() const { return tick_; }

 private:
  double timeout_s_;
  double reannounce_s_;
  uint64_t tick_ = 0;
  std::optional<Tick> answer_;
  bool stop_ = false;
  std::optional<uint64_t> stop_total_;  // windows a stop answering our tick counts
  double waiting_since_s_ = 0;
  double announced_at_s_ = 0;
};

}  // namespace smart::wire
