// Fuzz target: the QoS profile YAML, down to the Cyclone XML it renders and the QoS objects.
#include "fuzz_input.hpp"
#include "smart/config/yaml_checks.hpp"
#include "smart/dds/domain.hpp"
#include "smart/dds/qos_profile.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace smart::dds;
  try {
    const auto p = parse_qos_profile(std::string(smart::fuzz::text_of(data, size)), "fuzz.yaml");
    (void)render_cyclone_config(p.domain_config());
    for (const auto role : {TopicRole::kAction, TopicRole::kProgress, TopicRole::kState,
                            TopicRole::kClock, TopicRole::kStatus, TopicRole::kShard,
                            TopicRole::kPlan}) {
      (void)p.topic(role).to_dds();
    }
  } catch (const smart::config::ConfigError&) {
  }
  return 0;
}
