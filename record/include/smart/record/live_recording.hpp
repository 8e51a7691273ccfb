// Contract: a run recorded while it goes (`smart run --mcap`; issue 30: the recording's cost
// hidden beside the run instead of added after it). The same RunRecorder and the same start and
// end as export.hpp, fed the rows the run's results files get: each states.csv row as the file
// gets it (the text results::append_row made; read back as the export reads it) and each
// action's finish (on_action_finished, the time actions.csv gets, as_written). The producers
// only queue;
// the recorder runs on its own thread, compression included, at idle priority (SCHED_IDLE: it
// takes only the CPU the run leaves; what is left when the run ends is done by finish()). The
// queue is not bounded: a recorder that falls behind holds rows (80 bytes each), never slows the
// run. States are held until the newest state is lag_s of sim
// time past them, so that every action finished before a state reached the recorder first
// (progress reaches the monitor as its states do, far within 2 s of sim time). The file is then
// the one `smart export mcap` makes of the run's results folder, byte for byte (readers_mcap
// compares them); an action heard later than that would be recorded late, never lost.
// finish() after the run (its results folder written) attaches the folder's files, writes the
// summary and renames <out>.part to <out>; it throws what the recorder or the sink threw
// (std::invalid_argument for rows outside the fleet, std::runtime_error for the file). Without
// finish() the destructor stops the thread and removes <out>.part.
// A plan's run only (lifelong and resumed runs are recorded from their results afterwards).
#pragma once

#include <condition_variable>
#include <deque>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "smart/monitor/instance.hpp"
#include "smart/monitor/results_format.hpp"
#include "smart/record/export.hpp"
#include "smart/record/recorder.hpp"

namespace smart::record {

class FileSink;  // recording_parts.hpp

struct LiveRecordingSetup {
  std::filesystem::path out;
  RecorderOptions options;
  uint64_t run_id = 0;
  const monitor::Instance* instance = nullptr;  // the run's plan (its grid is the map); outlives
  double cell_m = 1.0;
  double robot_radius_m = 0.1;
  double lag_s = 2.0;
};

class LiveRecording {
 public:
  explicit LiveRecording(LiveRecordingSetup setup);  // opens <out>.part, writes map and plans
  ~LiveRecording();
  LiveRecording(const LiveRecording&) = delete;
  LiveRecording& operator=(const LiveRecording&) = delete;

  // A states.csv row as results::append_row wrote it (with its newline); any thread.
  void state(std::string_view line);
  void action_finished(uint32_t robot, uint32_t seq, double t_s);  // any thread
  // Takes no more rows and waits for the recorder's thread (finish() does it too).
  void stop();
  // CPU seconds the recording used beside the run (its thread and its chunk threads), once
  // stopped: the run's own CPU is the process's minus this.
  double cpu_s() const;
  ExportReport finish(const std::filesystem::path& results_dir);

 private:
  struct Item {
    bool is_state;
    uint32_t robot = 0, seq = 0;  // a progress
    double t_s = 0;
    std::size_t at = 0, length = 0;  // a state's line in the batch's text
  };
  struct Batch {
    std::vector<Item> items;
    std::string text;
  };
  void loop();
  void consume(const Batch& batch);
  void release(bool all);

  LiveRecordingSetup setup_;
  std::filesystem::path part_;
  ExportReport report_;
  std::unique_ptr<FileSink> sink_;
  std::unique_ptr<RunRecorder> rec_;
  std::deque<results::StateRow> held_;
  double newest_s_ = 0;
  std::mutex m_;
  std::condition_variable cv_;
  Batch incoming_;
  bool stop_ = false, finished_ = false;
  std::exception_ptr error_;
  double thread_cpu_s_ = 0;
  std::thread thread_;
};

}  // namespace smart::record
