// Fuzz target: the robot model YAML. Bad text must end in ConfigError, nothing else.
#include "fuzz_input.hpp"
#include "smart/agent/robot_model.hpp"
#include "smart/config/yaml_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    (void)smart::agent::parse_robot_model(std::string(smart::fuzz::text_of(data, size)),
                                          "fuzz.yaml");
  } catch (const smart::config::ConfigError&) {
  }
  return 0;
}
