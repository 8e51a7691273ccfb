// Contract: when one shard of a sharded sim (shard.hpp, docs/simulation.md "Sharded sim") may
// apply a period's exchanges, announce a tick, step or give up: a pure state machine shaped like
// the monitor's RunSupervisor (events in, decisions out; no DDS, no clock read, deterministic),
// around the lock-step HostHandshake (idl/…/wire/lockstep.hpp).
// Events: this shard's own exchange of a period went out (sent), another shard's exchange of a
// period arrived (received, after the wire checks and the one-writer-per-shard guard), the
// monitor's answer (on_answer), the time (timed_out, should_reannounce).
// The rule:
// - A period is applied once every shard's exchange of it is in (ready, then apply): the pump
//   adopts the robots handed to it and shows the neighbours' ghosts.
// - The lead (shard 0) then announces the tick to the monitor with the fleet's finished actions:
//   the sum of every shard's finished total of that period (announced_total). The monitor sees
//   one sim host.
// - Every shard steps once its period is applied and the monitor's answer to the tick is in with
//   the windows received adding up to it (may_step). Shards are never more than one period apart
//   (a shard steps only after every shard's exchange of its period), so exchanges of any other
//   period than the current one and the next are ignored.
// - A shard that waits (not stepping) reannounce_s after its exchange went out sends its last two
//   exchanges again (should_repeat): DDS lost one now and then on its way to one shard.
// - A shard gives up after timeout_s without progress: waiting for the named shards' exchanges
//   while its period is not applied, else for the monitor. The wait runs from this shard's last
//   announcement: the lead's to the monitor (or its start), another shard's own exchange.
// - Start-up gets join_s instead (the monitor's join window, 4 x timeout_s when `smart run`
//   starts its sim): the exchanges of periods 0 and 1 wait that long, as shards come up at
//   different times (by hand, on several hosts, or on a loaded machine building their worlds)
//   and period 1 is each shard's first step, which takes the run's first windows.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "smart/wire/lockstep.hpp"

namespace smart::sim {

struct ShardTimeout {
  enum class Waiting { kNothing, kShards, kMonitor };
  Waiting waiting = Waiting::kNothing;
  uint64_t tick = 0;
  std::vector<uint32_t> missing;  // kShards: the shards whose exchange of `tick` is not in
  double waited_s = 0;            // the wait that ran out: timeout_s, or join_s at start-up
};

class ShardBarrier {
 public:
  // Throws std::invalid_argument unless 2 <= shards, shard < shards and join_s >= timeout_s.
  ShardBarrier(uint32_t shard, uint32_t shards, double timeout_s, double reannounce_s,
               double join_s);
  // Exchanges of periods up to this one wait join_s (start-up and every shard's first step).
  static constexpr uint64_t kLastJoinPeriod = wire::kLastJoinTick;
  bool lead() const { return shard_ == 0; }
  uint64_t tick() const { return tick_; }
  bool applied() const { return applied_; }

  // This shard's exchange of `tick` went out with the actions its host reported finished: 0 at
  // the start, then the period after each step. Throws std::logic_error for any other tick.
  void sent(uint64_t tick, uint64_t finished_total, double now_s);
  // Another shard's exchange of `tick`; a repeat replaces the first. False: ignored (this shard's
  // own number, a shard out of range, or a period neither current nor next).
  bool received(uint32_t shard, uint64_t tick, uint64_t finished_total);
  // Every shard's exchange of the current period is in and it is not applied yet.
  bool ready() const;
  // The pump applied the period (call once ready()); the lead announces the tick now.
  void apply(double now_s);
  // The lead's announcement of the applied period: the fleet's finished actions.
  uint64_t announced_total() const { return announced_total_; }

  void on_answer(const wire::Tick& answer) { handshake_.on_answer(answer); }
  bool stop() const { return handshake_.stop(); }
  bool may_step(uint64_t run_id, uint64_t windows_received) const {
    return applied_ && handshake_.may_step(run_id, windows_received);
  }
  // The lead announces the applied tick again (a monitor that joined late missed it).
  bool should_reannounce(double now_s) const {
    return lead() && applied_ && handshake_.should_reannounce(now_s);
  }
  void reannounced(double now_s) { handshake_.reannounced(now_s); }
  // A shard that has not stepped for reannounce_s since its exchange went out (or went out
  // again) sends its kept exchanges again, its period's and the one before (the others are at
  // most one period behind): a reliable transient-local exchange can fail to reach one shard
  // (CI stop 52: shard 3's exchange of period 0 reached shards 0 and 1, never 2, nothing
  // refused), and that shard would wait for it while the others wait for it. Receivers drop a
  // repeat they have (shard_host.hpp).
  bool should_repeat(double now_s) const {
    return started_ && now_s - repeated_at_s_ > reannounce_s_;
  }
  void repeated(double now_s) { repeated_at_s_ = now_s; }
  ShardTimeout timed_out(double now_s) const;
  // What the shard waits for now, however long: the named shards' exchanges of its period (not
  // applied yet), else the monitor's answer to its tick, else nothing (waited_s is 0). A stop
  // that comes meanwhile is reported with it: the monitor gave up while the fleet waited.
  ShardTimeout waiting() const;

 private:
  void announced(uint64_t tick, double now_s);
  std::vector<uint32_t> missing() const;  // shards whose exchange of the period is not in

  uint32_t shard_, shards_;
  wire::HostHandshake handshake_;
  double timeout_s_, reannounce_s_, join_s_;
  double repeated_at_s_ = 0;    // this shard's exchange last went out (or out again)
  double waiting_since_s_ = 0;  // the handshake's: this shard's last announcement
  uint64_t tick_ = 0;
  bool started_ = false;
  bool applied_ = false;
  uint64_t own_total_ = 0;
  uint64_t announced_total_ = 0;
  std::map<uint64_t, std::map<uint32_t, uint64_t>> totals_;  // period -> shard -> finished
};

}  // namespace smart::sim
