#include "smart/agent/action_queue.hpp"

namespace smart::agent {

ActionQueue::Snapshot ActionQueue::snapshot() const {
  return {run_id_, started_, finished_seq_, {pending_.begin(), pending_.end()}, duplicates_};
}

void ActionQueue::restore(const Snapshot& s) {
  run_id_ = s.run_id;
  started_ = s.started;
  finished_seq_ = s.finished_seq;
  pending_.assign(s.pending.begin(), s.pending.end());
  duplicates_ = s.duplicates;
}

ActionQueue::Result ActionQueue::apply(uint64_t run_id, const std::vector<AgentAction>& window) {
  if (started_ && run_id < run_id_) return Result::kStaleRun;
  if (!started_ || run_id > run_id_) {
    // A new run, or a restarted agent: trust the monitor's idea of what is finished.
    run_id_ = run_id;
    started_ = true;
    pending_.clear();
    finished_seq_ = window.empty() ? -1 : static_cast<int64_t>(window.front().seq) - 1;
  }
  bool added = false;
  for (const auto& a : window) {
    const int64_t next =
        pending_.empty() ? finished_seq_ + 1 : static_cast<int64_t>(pending_.back().seq) + 1;
    const auto seq = static_cast<int64_t>(a.seq);
    if (seq < next) {
      ++duplicates_;
      continue;
    }
    if (seq > next) return added ? Result::kAccepted : Result::kGap;
    pending_.push_back(a);
    added = true;
  }
  return added ? Result::kAccepted : Result::kUnchanged;
}

void ActionQueue::finish_front() {
  finished_seq_ = pending_.front().seq;
  pending_.pop_front();
}

}  // namespace smart::agent
