// Contract: describes the machine a benchmark ran on (CPU model, cores, memory, kernel) and the
// process's peak resident memory, for benchmark output and docs/performance.md.
#pragma once

#include <string>

#include "smart/common/memory.hpp"

namespace smart::tools {

std::string machine_description();
using common::peak_rss_mb;

}  // namespace smart::tools
