// Contract: a finished run's results folder as an MCAP file (`smart run --mcap`, `smart export
// mcap`; record/export.hpp), with its topics listed on standard output like `mcap info`. Not in
// an agent-only build (record/ is not built there).
#pragma once

#include <filesystem>

#include "smart/record/export.hpp"
#include "smart/record/recorder.hpp"
#include "smart/tools/run_options.hpp"

namespace smart::tools {

// Throws std::invalid_argument for a damaged results folder, std::runtime_error when the file
// cannot be written.
void record_run(const std::filesystem::path& results_dir, const std::filesystem::path& mcap,
                const record::RecorderOptions& options);
// What record_run prints of a recording (also of one made while the run went).
void print_recording(const record::ExportReport& report, const std::filesystem::path& mcap);
// The recording options `smart run` gives (its ROS namespace and chosen robots).
record::RecorderOptions run_recorder_options(const MonitorCliOptions& o);

}  // namespace smart::tools
