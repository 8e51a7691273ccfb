#include "smart/tools/child_process.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace smart::tools {
namespace {

using namespace std::chrono_literals;

TEST(ChildProcess, ReportsExitCodeAndPeakMemoryOnceEnded) {
  ChildProcess p({"/bin/sh", "-c", "exit 3"});
  const auto rc = p.wait(10s);
  ASSERT_TRUE(rc.has_value());
  EXPECT_EQ(*rc, 3);
  ASSERT_TRUE(p.peak_rss_mb().has_value());
  EXPECT_GT(*p.peak_rss_mb(), 0.1);  // a shell needs more than 100 KiB
  EXPECT_LT(*p.peak_rss_mb(), 1000.0);
}

TEST(ChildProcess, NoPeakMemoryWhileRunningAndTerminateReportsTheSignal) {
  ChildProcess p({"/bin/sleep", "30"});
  EXPECT_TRUE(p.running());
  EXPECT_FALSE(p.peak_rss_mb().has_value());
  EXPECT_EQ(p.terminate(), 128 + 15);  // SIGTERM
  EXPECT_FALSE(p.running());
  EXPECT_TRUE(p.peak_rss_mb().has_value());
}

TEST(ChildProcess, AMissingProgramIsAnErrorNamingIt) {
  // glibc's posix_spawn reports a failed exec to the parent (ENOENT).
  try {
    ChildProcess p({"/nonexistent/smart-xyz"});
    FAIL() << "no error for a missing program";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/smart-xyz"), std::string::npos);
  }
}

}  // namespace
}  // namespace smart::tools
