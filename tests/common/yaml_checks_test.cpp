#include "smart/config/yaml_checks.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace smart::config {
namespace {

using ::testing::HasSubstr;

template <class Fn>
std::string error_of(Fn fn) {
  try {
    fn();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(YamlChecks, NumberRangeNamesKeyAndLine) {
  const auto root = load("a: 1\nspeed: -2\n", "r.yaml");
  EXPECT_DOUBLE_EQ(number("r.yaml", root["a"], "a", 0, 5), 1.0);
  EXPECT_THAT(error_of([&] { number("r.yaml", root["speed"], "speed", 0, 5); }),
              HasSubstr("r.yaml:2:8: 'speed' is -2 but must be from 0 to 5"));
}

TEST(YamlChecks, SyntaxErrorsAndUnknownKeys) {
  EXPECT_THAT(error_of([] { load("a: [1,\n", "x.yaml"); }), HasSubstr("x.yaml:"));
  const auto root = load("good: 1\nbda: 2\n", "x.yaml");
  EXPECT_THAT(error_of([&] {
                reject_unknown("x.yaml", root, "robot", {"good", "bad"});
              }),
              HasSubstr("x.yaml:2:1: unknown key 'bda' in 'robot'; known keys: good, bad"));
  EXPECT_THAT(error_of([] { read_file("/nonexistent.yaml", "robot"); }),
              HasSubstr("/nonexistent.yaml: cannot open the robot file"));
}

// Found by fuzzing (tests/fuzz/corpus/robot_yaml/regression_non_scalar_key.yaml): a key that is
// a sequence escaped as YAML::BadConversion, not a ConfigError naming the file and line.
TEST(YamlChecks, ANonScalarKeyIsAConfigErrorNotABadConversion) {
  const auto root = load("good: 1\n[a, b]: 2\n", "k.yaml");
  EXPECT_THAT(error_of([&] { reject_unknown("k.yaml", root, "robot", {"good"}); }),
              HasSubstr("k.yaml:2:1: a key in 'robot' is not a plain word"));
}

TEST(YamlChecks, ChoiceListsOptions) {
  const auto root = load("kind: maybe\n", "c.yaml");
  EXPECT_THAT(error_of([&] {
                choice<int>("c.yaml", root["kind"], "kind", {{"yes", 1}, {"no", 0}});
              }),
              HasSubstr("'kind' is 'maybe'; use one of: no, yes"));
  EXPECT_THAT(error_of([&] { millis("c.yaml", load("t: -1", "c.yaml")["t"], "t"); }),
              HasSubstr("negative"));
}

}  // namespace
}  // namespace smart::config
