// Fuzz target: the MovingAI scenario reader, and the check of a scenario against a small map.
#include "fuzz_input.hpp"
#include "smart/grid/map_reader.hpp"
#include "smart/grid/problem.hpp"
#include "smart/grid/scen_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace smart::grid;
  static const Grid grid =
      parse_map("type octile\nheight 3\nwidth 4\nmap\n....\n.@..\n....\n", "m");
  try {
    const auto scen = parse_scen(smart::fuzz::text_of(data, size), "fuzz.scen");
    (void)check_scen_against_map(scen, grid);
  } catch (const InputError&) {
  }
  return 0;
}
