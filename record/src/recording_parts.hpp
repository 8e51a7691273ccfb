// The parts of a run's recording that export.cpp (from a results folder) and
// live_recording.cpp (while the run goes) share, so that both make the same file: the sink,
// the start (map, then the plan view when there is a plan) and the end (the results folder's
// files and the run's inputs attached, the summary written). Internal to record/.
#pragma once

#include <filesystem>
#include <fstream>
#include <string_view>

#include "smart/grid/grid.hpp"
#include "smart/monitor/instance.hpp"
#include "smart/record/export.hpp"
#include "smart/record/recorder.hpp"

namespace smart::record {

class FileSink : public ByteSink {
 public:
  explicit FileSink(const std::filesystem::path& path);  // throws std::runtime_error
  void write(std::string_view bytes) override;
  void close();
  uint64_t bytes() const { return bytes_; }

 private:
  std::filesystem::path path_;
  std::ofstream out_;
  uint64_t bytes_ = 0;
};

// report.robots must be set; instance may be null (no plan: no paths, no markers).
void start_recording(RunRecorder& rec, const grid::Grid& map, double cell_m,
                     const monitor::Instance* instance, double robot_radius_m,
                     ExportReport& report);
// Reads results_dir's summary.json (std::invalid_argument when missing or malformed).
void end_recording(RunRecorder& rec, const std::filesystem::path& results_dir,
                   ExportReport& report);

}  // namespace smart::record
