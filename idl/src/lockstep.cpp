#include "smart/wire/lockstep.hpp"

#include <algorithm>

namespace smart::wire {

uint64_t SyncCounter::raise(uint32_t robot, uint64_t mark) {
  if (mark <= marks_[robot]) return 0;
  const uint64_t grew = mark - marks_[robot];
  marks_[robot] = mark;
  total_ += grew;
  return grew;
}

void SyncCounter::reset() {
  std::fill(marks_.begin(), marks_.end(), 0);
  total_ = 0;
}

void MonitorHandshake::on_tick(const Tick& t) {
  if (answered_any_ && t.tick < last_answered_) return;
  if (!pending_ || t.tick >= pending_->tick) pending_ = t;
}

Tick MonitorHandshake::answer(uint64_t run_id, uint64_t windows_sent, bool stop) {
  const Tick announced = *pending_;
  pending_.reset();
  last_answered_ = announced.tick;
  answered_any_ = true;
  last_answer_ = Tick{run_id, announced.tick, announced.sim_time_s, windows_sent, stop};
  return *last_answer_;
}

void HostHandshake::announced(uint64_t tick, double now_s) {
  tick_ = tick;
  answer_.reset();
  waiting_since_s_ = now_s;
  announced_at_s_ = now_s;
}

void HostHandshake::reannounced(double now_s) { announced_at_s_ = now_s; }

void HostHandshake::on_answer(const Tick& a) {
  if (a.stop) stop_ = true;
  if (a.stop && a.tick == tick_) stop_total_ = a.sync_total;
  if (a.tick == tick_) answer_ = a;
}

bool HostHandshake::may_step(uint64_t run_id, uint64_t windows_received) const {
  return answer_ && answer_->run_id == run_id && answer_->sync_total == windows_received;
}

bool HostHandshake::should_reannounce(double now_s) const {
  return !answer_ && now_s - announced_at_s_ > reannounce_s_;
}

}  // namespace smart::wire
