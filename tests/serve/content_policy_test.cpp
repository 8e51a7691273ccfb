// The viewer's Content-Security-Policy (serve/content_policy.hpp).
#include "smart/serve/content_policy.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace smart::serve {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(ContentPolicy, AScriptsHashSourceIsTheBase64OfItsSha256) {
  // SHA-256 of the empty string, base64 (FIPS 180-4 test vector).
  EXPECT_EQ(script_hash_source(""), "'sha256-47DEQpj8HBSa+/TImW+5JCeuQeRkm5NMpJWZG3hSuFU='");
}

TEST(ContentPolicy, OnlyTheServersFilesAndThePagesOwnInlineScriptsMayRun) {
  const std::string map = "\n  { \"imports\": { \"three\": \"./vendor/three.module.js\" } }\n";
  const std::string html = "<html><body><script type=\"importmap\">" + map +
                           "</script><script type=\"module\" src=\"./src/main.js\"></script>"
                           "</body></html>";
  const auto csp = content_security_policy(html);
  EXPECT_THAT(csp, HasSubstr("script-src 'self' " + script_hash_source(map) + ";"));
  EXPECT_THAT(csp, HasSubstr("default-src 'self'"));
  EXPECT_THAT(csp, HasSubstr("object-src 'none'"));
  EXPECT_THAT(csp, Not(HasSubstr("unsafe-inline")));
  EXPECT_THAT(content_security_policy(""), HasSubstr("script-src 'self';"));
}

}  // namespace
}  // namespace smart::serve
