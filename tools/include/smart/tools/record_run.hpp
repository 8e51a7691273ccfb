// Contract: a finished run's results folder as an MCAP file (`smart run --mcap`, `smart export
// mcap`; record/export.hpp), with its topics listed on standard output like `mcap info`. Not in
// an agent-only build (record/ is not built there).
#pragma once

#include <filesystem>

#include "smart/record/recorder.hpp"

namespace smart::tools {

// Throws std::invalid_argument for a damaged results folder, std::runtime_error when the file
// cannot be written.
void record_run(const std::filesystem::path& results_dir, const std::filesystem::path& mcap,
                const record::RecorderOptions& options);

}  // namespace smart::tools
