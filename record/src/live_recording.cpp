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

void LiveRecording::state(std::string_view line) {
  std::lock_guard lock(m_);
  incoming_.items.push_back({true, 0, 0, 0.0, incoming_.text.size(), line.size()});
  incoming_.text.append(line);
  if (incoming_.items.size() == kBatch) cv_.notify_one();
}

void LiveRecording::action_finished(uint32_t robot, uint32_t seq, double t_s) {
  std::lock_guard lock(m_);
  incoming_.items.push_back({false, robot, seq, t_s, 0, 0});
  if (incoming_.items.size() == kBatch) cv_.notify_one();
}

void LiveRecording::loop() {
  // SCHED_IDLE (sched(7)): the recording takes the CPU the run leaves, never the run's. What it
  // has not done when the run ends, finish() does at normal priority.
  sched_param idle{};
  (void)pthread_setschedparam(pthread_self(), SCHED_IDLE, &idle);
  Batch batch;
  for (bool stop = false; !stop;) {
    {
      std::unique_lock lock(m_);
      cv_.wait_for(lock, std::chrono::milliseconds(50),
                   [this] { return stop_ || incoming_.items.size() >= kBatch; });
      std::swap(batch, incoming_);
      stop = stop_;
    }
    if (!error_) {
      try {
        consume(batch);
      } catch (...) {
        error_ = std::current_exception();  // finish() throws it; the rest is dropped
      }
    }
    batch.items.clear();
    batch.text.clear();
  }
  thread_cpu_s_ = common::thread_cpu_seconds();
}

double LiveRecording::cpu_s() const {
  return thread_cpu_s_ + (rec_ ? rec_->background_cpu_s() : 0.0);
}

void LiveRecording::consume(const Batch& batch) {
  for (const auto& item : batch.items) {
    if (!item.is_state) {
      rec_->progress(results::as_written(item.t_s), item.robot, static_cast<int32_t>(item.seq));
      continue;
    }
    auto line = std::string_view(batch.text).substr(item.at, item.length);
    if (!line.empty() && line.back() == '\n') line.remove_suffix(1);
    const auto row = results::parse_state_line(line);
    if (!row) {
      throw std::invalid_argument("recording: not a states.csv row: " + std::string(line));
    }
    held_.push_back(*row);
    newest_s_ = std::max(newest_s_, row->t_s);
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
