// Contract: the file edge of recordings: a results folder (monitor/results_format.hpp) as an MCAP
// file (recorder.hpp). Reads summary.json (robots, cell_m, run_id, files), the map
// (lifelong.map beside the results, else the one summary.json names), the plan when summary.json
// names one that can still be read (each robot's planned path; otherwise recorded without plans
// and said so in the report), actions.csv (progress), events.csv and states.csv, streamed a line
// at a time. The results files but states.csv, lifelong.map and the run's inputs are attached
// (import.hpp reads them back; an input that cannot be read is a note). Writes <out>.part and
// renames it to <out> once complete, so a failed export leaves no half file. Throws
// std::invalid_argument naming the file (and line) that is missing or malformed and what to do,
// std::runtime_error when the output cannot be written; never exits.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "smart/record/recorder.hpp"

namespace smart::record {

// `smart export mcap RESULTS_DIR`'s file when none is named: RESULTS_DIR/run.mcap.
inline constexpr std::string_view kDefaultMcap = "run.mcap";

struct ExportReport {
  uint64_t messages = 0;
  uint64_t bytes = 0;
  std::size_t robots = 0;
  std::vector<std::string> notes;        // what was left out and why
  std::vector<std::string> attachments;  // names (import.hpp)
  std::vector<McapWriter::ChannelCount> channels;
};

ExportReport export_mcap(const std::filesystem::path& results_dir, const std::filesystem::path& out,
                         const RecorderOptions& options);

}  // namespace smart::record
