// JSON from outside within limits (serve/bounded_json.hpp).
#include "smart/serve/bounded_json.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>

namespace smart::serve {
namespace {

using ::testing::HasSubstr;

std::string refusal(const std::string& text) {
  try {
    parse_bounded_json(text, "summary.json");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

// Issue 25: a 200 KB summary.json nested 100 000 deep was accepted, then crashed the server.
TEST(BoundedJson, DeepNestingTooManyBytesAndNonJsonAreRefusedNamingTheSource) {
  EXPECT_THAT(refusal(std::string(100000, '[') + std::string(100000, ']')),
              HasSubstr("summary.json nests deeper than 32 levels"));
  EXPECT_THAT(refusal(std::string(kMaxJsonBytes + 1, ' ')),
              HasSubstr("summary.json is 16777217 bytes; at most 16777216"));
  EXPECT_THAT(refusal("{\"robots\": "), HasSubstr("summary.json is not JSON"));
  EXPECT_THAT(refusal("{\"robots\": " + std::string(400, '9') + "}"),
              HasSubstr("summary.json cannot be read as JSON"));
}

TEST(BoundedJson, ASummaryWithinTheLimitsIsRead) {
  const auto j = parse_bounded_json(R"({"robots": 20, "files": {"map": "m.map"}, "a": [[[1]]]})",
                                    "summary.json");
  EXPECT_EQ(j["robots"], 20);
  EXPECT_EQ(j["files"]["map"], "m.map");
  EXPECT_EQ(refusal(std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']')), "accepted");
}

}  // namespace
}  // namespace smart::serve
