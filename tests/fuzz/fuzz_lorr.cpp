// Fuzz target: the lifelong problem readers (grid/lorr.hpp): a LoRR problem JSON, its agents and
// tasks files against a small map, and LSMART's JSON maps. The first byte picks the reader ('0'
// to '3', modulo 4), the rest is the file.
#include "fuzz_input.hpp"
#include "smart/grid/lorr.hpp"
#include "smart/grid/map_reader.hpp"
#include "smart/grid/problem.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace smart::grid;
  if (size == 0) return 0;
  static const Grid grid =
      parse_map("type octile\nheight 3\nwidth 4\nmap\n....\n.@..\n..@.\n", "m");
  const std::string_view text = smart::fuzz::text_of(data + 1, size - 1);
  try {
    switch (data[0] % 4) {
      case 0:
        (void)parse_lorr_spec(text, "fuzz.json");
        break;
      case 1:
        (void)parse_lorr_agents(text, "fuzz.agents", grid, 0);
        break;
      case 2: {
        const auto tasks = parse_lorr_tasks(text, "fuzz.tasks", grid);
        (void)check_tasks_reachable(grid, {{0, 0}}, tasks, "fuzz.tasks");
        break;
      }
      default:
        (void)parse_lsmart_map(text, "fuzz.json");
    }
  } catch (const InputError&) {
  }
  return 0;
}
