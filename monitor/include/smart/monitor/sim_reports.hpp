// Contract: `smart run`'s second opinion on a success (issue 25, "never a false success"). The
// monitor's verdict rests on what reached it over DDS; each sim host it started also writes its
// own report (sim-<shard>.json, results_format.hpp). A success stands only when every sim host
// reported, none failed, and their collision counts add up to what the monitor was told; else
// the run is unverified and the error says which host said what. Pure.
#pragma once

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "smart/monitor/results_format.hpp"
#include "smart/monitor/run_supervisor.hpp"

namespace smart::monitor {

// Shard s's report, or why it could not be read.
using SimWord = std::variant<results::SimReport, std::string>;

// Why the sim hosts' own words contradict the monitor's success, or nothing (also when the run
// did not succeed: a failure needs no second opinion).
std::optional<std::string> sim_disagreement(const MonitorResult& r,
                                            const std::vector<SimWord>& reports);
// Turns a success the sim hosts contradict into an unverified run naming the disagreement.
void apply_sim_reports(MonitorResult& r, const std::vector<SimWord>& reports);

}  // namespace smart::monitor
