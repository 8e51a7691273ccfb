// Contract: a recording made here (`smart run --mcap`, `smart export mcap`; export.hpp) back as a
// results folder (monitor/results_format.hpp), so `smart serve --open run.mcap` replays it in the
// viewer on a machine without the run's files. The recording carries the results files as MCAP
// attachments named as in results_format.hpp (all but states.csv), lifelong.map when the run had
// one, and the run's inputs as "input/<map|scen|plan|robot>/<file name>"; states.csv is rebuilt
// from the smart/state channel (one row per RobotState, written as the run wrote it, so the rows
// read back equal). Inputs land in <results_dir>/inputs/<key>/ and summary.json's "files" is
// pointed at them. The MCAP file is untrusted (mcap_reader.hpp): attachment names outside that
// list are skipped (a note says which), file names are reduced to letters, digits, '.', '-' and
// '_', states.csv may grow to options.max_states_bytes, every RobotState must decode
// (record/cdr.hpp) with finite numbers. Throws std::invalid_argument (McapError for the file's
// structure) naming the file, the byte or the message and what to do; std::runtime_error when the
// folder cannot be written; after a failure the folder may hold part of the files (give a scratch
// folder). A recording without summary.json or smart/state is refused by name
// (not one made here: open it in Foxglove).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "smart/record/mcap_reader.hpp"

namespace smart::record {

// The attachment names export.hpp gives the run's inputs: "input/<key>/<file name>".
inline constexpr std::string_view kInputAttachmentPrefix = "input/";

struct ImportOptions {
  McapLimits limits;
  uint64_t max_states_bytes = uint64_t{8} << 30;
};

struct ImportReport {
  uint64_t states = 0;             // rows of states.csv
  std::vector<std::string> files;  // written, relative to the results folder
  std::vector<std::string> notes;  // what was skipped and why
};

ImportReport import_mcap(const std::filesystem::path& mcap,
                         const std::filesystem::path& results_dir,
                         const ImportOptions& options = {});

}  // namespace smart::record
