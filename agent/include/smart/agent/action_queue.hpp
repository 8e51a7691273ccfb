// Contract: the agent's FIFO of actions, fed by action windows from the monitor.
// Windows are state, not commands: applying the same or an overlapping window again changes
// nothing, an older window (seqs already queued or finished) is ignored, and a window that
// would leave a gap is ignored from the gap on. A window of a newer run (larger run id) starts
// the queue afresh at the window's first seq, so a restarted agent resumes where the monitor
// says it is; windows of an older run are ignored.
#pragma once

#include <cstdint>
#include <deque>
#include <vector>

#include "smart/agent/types.hpp"

namespace smart::agent {

class ActionQueue {
 public:
  enum class Result { kAccepted, kUnchanged, kGap, kStaleRun };

  // Everything the queue holds, to continue it elsewhere (a robot moving between sim shards).
  struct Snapshot {
    uint64_t run_id = 0;
    bool started = false;
    int64_t finished_seq = -1;
    std::vector<AgentAction> pending;
    uint64_t duplicates = 0;
  };
  Snapshot snapshot() const;
  void restore(const Snapshot& s);

  Result apply(uint64_t run_id, const std::vector<AgentAction>& window);

  const std::deque<AgentAction>& pending() const { return pending_; }
  bool empty() const { return pending_.empty(); }
  const AgentAction& front() const { return pending_.front(); }
  // Marks the front action finished.
  void finish_front();

  int64_t finished_seq() const { return finished_seq_; }  // -1: none
  uint64_t run_id() const { return run_id_; }
  uint64_t duplicates_ignored() const { return duplicates_; }

 private:
  uint64_t run_id_ = 0;
  bool started_ = false;
  int64_t finished_seq_ = -1;
  std::deque<AgentAction> pending_;
  uint64_t duplicates_ = 0;
};

}  // namespace smart::agent
