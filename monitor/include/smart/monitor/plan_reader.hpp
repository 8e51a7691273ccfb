// Contract: reads a MAPF plan from text in one of these formats:
// - smart: SMART / MAPF-LNS2 path lists, one robot per line: "Agent i:(a,b,t)->(a,b,t)->..."
//   (timed, t may be non-integer) or "Agent i:(a,b)->(a,b)->..." (untimed: step k at time k).
//   MAPF-LNS2's --outputPaths writes this with (row,col). The file does not say its axis order,
//   so `axis` is required for it.
// - lacam: LaCAM/PIBT result.txt: optional "key=value" header, "solution=", then one line per
//   timestep "t:(x,y),(x,y),..." with one position per robot (x = column by default).
// - yaml: libMultiRobotPlanning output, "schedule:" mapping agent names to lists of {x, y, t}.
// The format is detected from the text unless given. Robots must be numbered 0..N-1 without
// gaps or duplicates. Every problem found is reported at once (InputError with file, line and
// robot). No I/O: the caller reads the file.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "smart/monitor/vocabulary.hpp"

namespace smart::monitor {

struct PlanReadOptions {
  PlanFormat format = PlanFormat::kAuto;
  std::optional<AxisOrder> axis;
};

// kAuto when the text matches no known format.
PlanFormat detect_plan_format(std::string_view text);
Plan parse_plan(std::string_view text, const std::string& source, const PlanReadOptions& options);

AxisOrder parse_axis_order(const std::string& s);    // "xy" | "rowcol"
PlanFormat parse_plan_format(const std::string& s);  // "auto" | "smart" | "lacam" | "yaml"

}  // namespace smart::monitor
