#include "smart/record/live_recording.hpp"

#include <pthread.h>
#include <sched.h>

#include <chrono>

#include "recording_parts.hpp"
#include "smart/common/memory.hpp"

namespace smart::record {

namespace fs = std::filesystem;

namespace {
constexpr std::size_t kBatch = 4096;  // items handed over at once

results::StateRow as_written(results::StateRow r) {
  for (double* v :
       {&r.t_s, &r.x_m, &r.y_m, &r.yaw_rad, &r.v_mps, &r.w_radps, &r.left_mps, &r.right_mps}) {
    *v = results::as_written(*v);
  }
  return r;
}
}  // namespace

LiveRecording::LiveRecording(LiveRecordingSetup setup)
    : setup_(std::move(setup)), part_(setup_.out.string() + ".part") {
  // One thread does it all, compression included, at idle priority (below).
  setup_.options.mcap.background_chunks = false;
  if (!setup_.instance) throw std::invalid_argument("a live recording needs the run's plan");
  report_.robots = setup_.instance->actions.robots();
  sink_ = std::make_unique<FileSink>(part_);
  try {
    rec_ = std::make_unique<RunRecorder>(*sink_, setup_.options, report_.robots, setup_.run_id);
    start_recording(*rec_, setup_.instance->grid, setup_.cell_m, setup_.instance,
                    setup_.robot_radius_m, report_);
  } catch (...) {
    std::error_code ec;
    fs::remove(part_, ec);
    throw;
  }
  thread_ = std::thread([this] { loop(); });
}

LiveRecording::~LiveRecording() {
  stop();
  if (!finished_) {
    rec_.reset();
    sink_.reset();
    std::error_code ec;
    fs::remove(part_, ec);
  }
}

void LiveRecording::push(const Item& item) {
  std::lock_guard lock(m_);
  incoming_.push_back(item);
  if (incoming_.size() == kBatch) cv_.notify_one();
}

void LiveRecording::state(const results::StateRow& row) { push({true, row}); }

void LiveRecording::action_finished(uint32_t robot, uint32_t seq, double t_s) {
  results::StateRow r;
  r.t_s = t_s;
  r.robot = robot;
  r.queue = seq;
  push({false, r});
}

void LiveRecording::loop() {
  // SCHED_IDLE (sched(7)): the recording takes the CPU the run leaves, never the run's. What it
  // has not done when the run ends, finish() does at normal priority.
  sched_param idle{};
  (void)pthread_setschedparam(pthread_self(), SCHED_IDLE, &idle);
  std::vector<Item> batch;
  for (bool stop = false; !stop;) {
    {
      std::unique_lock lock(m_);
      cv_.wait_for(lock, std::chrono::milliseconds(50),
                   [this] { return stop_ || incoming_.size() >= kBatch; });
      batch.swap(incoming_);
      stop = stop_;
    }
    if (!error_) {
      try {
        consume(batch);
      } catch (...) {
        error_ = std::current_exception();  // finish() throws it; the rest is dropped
      }
    }
    batch.clear();
  }
  thread_cpu_s_ = common::thread_cpu_seconds();
}

double LiveRecording::cpu_s() const {
  return thread_cpu_s_ + (rec_ ? rec_->background_cpu_s() : 0.0);
}

void LiveRecording::consume(const std::vector<Item>& batch) {
  for (const auto& item : batch) {
    if (!item.is_state) {
      rec_->progress(results::as_written(item.row.t_s), item.row.robot,
                     static_cast<int32_t>(item.row.queue));
      continue;
    }
    held_.push_back(as_written(item.row));
    newest_s_ = std::max(newest_s_, held_.back().t_s);
    release(false);  // after each state: the same file however the rows were batched
  }
}

// In states.csv's order; the front waits until the newest state is lag_s past it.
void LiveRecording::release(bool all) {
  while (!held_.empty() && (all || held_.front().t_s <= newest_s_ - setup_.lag_s)) {
    rec_->state(held_.front());
    held_.pop_front();
  }
}

void LiveRecording::stop() {
  {
    std::lock_guard lock(m_);
    stop_ = true;
  }
  cv_.notify_one();
  if (thread_.joinable()) thread_.join();
}

ExportReport LiveRecording::finish(const fs::path& results_dir) {
  stop();
  try {
    if (error_) std::rethrow_exception(error_);
    release(true);
    end_recording(*rec_, results_dir, report_);
    sink_->close();
  } catch (...) {
    rec_.reset();
    sink_.reset();
    std::error_code ec;
    fs::remove(part_, ec);
    finished_ = true;
    throw;
  }
  fs::rename(part_, setup_.out);
  report_.bytes = sink_->bytes();
  finished_ = true;
  return report_;
}

}  // namespace smart::record
