// Fuzz target: an uploaded results folder as `smart serve` reads it (POST /api/results, --open):
// summary.json within its limits, states.csv into a recording within its bound and back,
// robots.csv and actions.csv rows. The input is the folder's files joined by "\n--8<--\n" in
// that order (summary.json, states.csv, robots.csv, actions.csv). The readers' error type is
// std::invalid_argument; anything else is a finding.
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_input.hpp"
#include "smart/monitor/results_format.hpp"
#include "smart/serve/bounded_json.hpp"
#include "smart/serve/recording.hpp"

namespace {

std::vector<std::string_view> files_of(std::string_view text) {
  constexpr std::string_view kCut = "\n--8<--\n";
  std::vector<std::string_view> out;
  std::size_t at = 0;
  while (out.size() < 3) {
    const auto cut = text.find(kCut, at);
    if (cut == std::string_view::npos) break;
    out.push_back(text.substr(at, cut - at));
    at = cut + kCut.size();
  }
  out.push_back(text.substr(std::min(at, text.size())));
  while (out.size() < 4) out.emplace_back();
  return out;
}

template <class Fn>
void reading(Fn fn) {
  try {
    fn();
  } catch (const std::invalid_argument&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace smart;
  const auto files = files_of(fuzz::text_of(data, size));
  reading([&] {
    const auto summary = serve::parse_bounded_json(files[0], "summary.json");
    (void)summary.dump();  // what GET /api/runs/{id} writes out again
    if (summary.is_object()) (void)summary.value(results::summary_key::kRobots, nlohmann::json());
  });
  reading([&] {
    const auto rows = serve::parse_states_csv(files[1]);
    serve::check_recording_size(rows, files[1].size());
    const auto rec = serve::decode_recording(serve::encode_recording(rows));
    if (rec.poses.size() != rec.times_s.size() * rec.robots) __builtin_trap();
  });
  reading([&] { (void)results::parse_robots_csv(files[2]); });
  reading([&] { results::for_each_action_row(files[3], [](const auto&, std::size_t) {}); });
  return 0;
}
