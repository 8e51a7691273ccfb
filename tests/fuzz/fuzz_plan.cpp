// Fuzz target: every plan format (the first byte picks SMART, LaCAM, YAML or detection, and the
// axis order); a plan that reads is also turned into actions.
#include "fuzz_input.hpp"
#include "smart/grid/problem.hpp"
#include "smart/monitor/action_builder.hpp"
#include "smart/monitor/plan_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace smart::monitor;
  if (size == 0) return 0;
  PlanReadOptions options;
  const PlanFormat formats[] = {PlanFormat::kAuto, PlanFormat::kSmart, PlanFormat::kLacam,
                                PlanFormat::kYaml};
  options.format = formats[data[0] % 4];
  if (data[0] & 4) options.axis = (data[0] & 8) ? AxisOrder::kRowCol : AxisOrder::kXY;
  try {
    const auto plan = parse_plan(smart::fuzz::text_of(data + 1, size - 1), "fuzz.plan", options);
    if (plan.paths.size() <= 64) (void)build_actions(plan, Heading::kEast);
  } catch (const smart::grid::InputError&) {
  }
  return 0;
}
