#include "smart/common/child_process.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <stdexcept>
#include <string>

namespace smart::common {
namespace {

using namespace std::chrono_literals;

TEST(ChildProcess, ReportsTheExitCode) {
  ChildProcess p({"/bin/sh", "-c", "exit 3"});
  const auto rc = p.wait(10s);
  ASSERT_TRUE(rc.has_value());
  EXPECT_EQ(*rc, 3);
  EXPECT_FALSE(p.running());
}

TEST(ChildProcess, TerminateReportsTheSignal) {
  ChildProcess p({"/bin/sleep", "30"});
  EXPECT_TRUE(p.running());
  EXPECT_FALSE(p.wait(50ms).has_value());
  EXPECT_EQ(p.terminate(), 128 + 15);  // SIGTERM
  EXPECT_FALSE(p.running());
}

TEST(ChildProcess, StdoutGoesToTheGivenFile) {
  const auto file = std::filesystem::temp_directory_path() /
                    ("smart_child_process_test_" + std::to_string(::getpid()));
  ChildProcess p({"/bin/sh", "-c", "echo hello"}, file);
  ASSERT_EQ(p.wait(10s).value_or(-1), 0);
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "hello");
  std::filesystem::remove(file);
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
}  // namespace smart::common
