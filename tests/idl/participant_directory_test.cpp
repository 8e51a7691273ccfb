// Who a participant is, from discovery: its GUID prefix, host, pid and process name.
#include "smart/dds/participant_directory.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "support/dds_test_support.hpp"

namespace smart::dds {
namespace {

using namespace std::chrono_literals;

TEST(ParticipantDirectory, NamesAParticipantByItsGuidHostAndPid) {
  Domain domain(test::kParticipantDirectory, test::loopback());
  Participant me(domain), other(domain);
  ParticipantDirectory directory(me);
  dds_guid_t guid;
  ASSERT_EQ(dds_get_guid(other.handle(), &guid), DDS_RETCODE_OK);
  char host[65] = {};
  ASSERT_EQ(gethostname(host, sizeof(host) - 1), 0);
  const std::string want =
      "participant " + guid_prefix(guid) + " (host " + host + ", pid " + std::to_string(getpid());
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  std::string got;
  while ((got = directory.describe(guid)).find("(host") == std::string::npos) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << got;
    std::this_thread::sleep_for(5ms);
  }
  EXPECT_EQ(got.substr(0, want.size()), want);
  EXPECT_EQ(guid_prefix(guid).size(), 26u);  // 12 bytes in hex, ':' every four
  EXPECT_EQ(directory.describe(std::nullopt), "a writer that left");
}

}  // namespace
}  // namespace smart::dds
