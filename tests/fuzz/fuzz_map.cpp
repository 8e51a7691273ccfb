// Fuzz target: the MovingAI map reader. Bad text must end in InputError, nothing else.
#include "fuzz_input.hpp"
#include "smart/grid/map_reader.hpp"
#include "smart/grid/problem.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    (void)smart::grid::parse_map(smart::fuzz::text_of(data, size), "fuzz.map");
  } catch (const smart::grid::InputError&) {
  }
  return 0;
}
