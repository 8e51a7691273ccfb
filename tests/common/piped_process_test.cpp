#include "smart/common/piped_process.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <optional>
#include <string>
#include <thread>

namespace smart::common {
namespace {

using namespace std::chrono_literals;
using Io = PipedProcess::Io;

// Generous: these are waits for events, the deadline only stops a broken test from hanging.
PipedProcess::Deadline soon() { return std::chrono::steady_clock::now() + 30s; }

TEST(PipedProcess, WritesAndReadsLines) {
  PipedProcess p("cat");
  ASSERT_EQ(p.write_line("hello", soon()), Io::kOk);
  ASSERT_EQ(p.write_line("world", soon()), Io::kOk);
  std::string line;
  ASSERT_EQ(p.read_line(line, 100, soon()), Io::kOk);
  EXPECT_EQ(line, "hello");
  ASSERT_EQ(p.read_line(line, 100, soon()), Io::kOk);
  EXPECT_EQ(line, "world");
}

TEST(PipedProcess, ASilentChildTimesOut) {
  PipedProcess p("sleep 30");
  std::string line;
  EXPECT_EQ(p.read_line(line, 100, std::chrono::steady_clock::now() + 50ms), Io::kTimeout);
}

TEST(PipedProcess, AChildThatExitsIsClosedWithItsExitCode) {
  PipedProcess p("echo last; exit 3");
  std::string line;
  ASSERT_EQ(p.read_line(line, 100, soon()), Io::kOk);
  EXPECT_EQ(line, "last");
  EXPECT_EQ(p.read_line(line, 100, soon()), Io::kClosed);
  // Its output may close a moment before its input: wait for the exit itself.
  std::optional<int> code;
  for (const auto until = soon(); !code && std::chrono::steady_clock::now() < until;) {
    code = p.exit_code();
  }
  EXPECT_EQ(code, 3);
  // Writing to it raises no SIGPIPE (this test would die of it).
  EXPECT_EQ(p.write_line("anyone?", soon()), Io::kClosed);
}

TEST(PipedProcess, ALineTooLongIsDroppedAndTheNextOneRead) {
  PipedProcess p("head -c 300000 /dev/zero | tr '\\0' x; echo; echo next");
  std::string line;
  EXPECT_EQ(p.read_line(line, 1000, soon()), Io::kTooLong);
  ASSERT_EQ(p.read_line(line, 1000, soon()), Io::kOk);
  EXPECT_EQ(line, "next");
}

// A child that floods one endless line: what is held stays within the bound and a read chunk.
TEST(PipedProcess, AnEndlessLineCostsBoundedMemory) {
  PipedProcess p("yes 2>/dev/null | tr -d '\\n' 2>/dev/null");
  std::string line;
  const auto until = std::chrono::steady_clock::now() + 300ms;
  EXPECT_EQ(p.read_line(line, 4096, until), Io::kTimeout);
  EXPECT_LE(p.buffered(), 4096u + 65536u);
}

// Regression: the deadline was checked only when the pipe was empty, so a reader taking lines
// from a child that writes them faster (`yes`, or a planner flooding stale replies under ASan)
// never timed out.
TEST(PipedProcess, AChildWritingFasterThanItIsReadStillTimesOut) {
  PipedProcess p("yes 2>/dev/null");
  std::string line;
  const auto deadline = std::chrono::steady_clock::now() + 200ms;
  const auto give_up = deadline + 30s;  // the guard of a broken test, not a time it needs
  Io io = Io::kOk;
  while (io == Io::kOk && std::chrono::steady_clock::now() < give_up) {
    io = p.read_line(line, 100, deadline);
  }
  EXPECT_EQ(io, Io::kTimeout);
}

TEST(PipedProcess, AChildNotReadingItsInputTimesOutTheWriter) {
  PipedProcess p("sleep 30");
  const std::string big(1 << 20, 'x');  // larger than a pipe's buffer
  EXPECT_EQ(p.write_line(big, std::chrono::steady_clock::now() + 100ms), Io::kTimeout);
  EXPECT_EQ(p.write_line("more", soon()), Io::kClosed);
}

bool process_gone(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string pid_text, name, state;
  return !(stat >> pid_text >> name >> state) || state == "Z";
}

// A command's own children end with it: a planner started through `cd dir && python3 ...` is
// not left running when the run ends.
TEST(PipedProcess, TheDestructorEndsTheCommandsChildrenToo) {
  pid_t sleeper = 0;
  {
    PipedProcess p("sleep 60 & echo $!; wait");
    std::string line;
    ASSERT_EQ(p.read_line(line, 100, soon()), Io::kOk);
    sleeper = std::stoi(line);
    ASSERT_FALSE(process_gone(sleeper));
  }
  for (const auto until = soon();
       !process_gone(sleeper) && std::chrono::steady_clock::now() < until;) {
    std::this_thread::sleep_for(1ms);
  }
  EXPECT_TRUE(process_gone(sleeper));
}

}  // namespace
}  // namespace smart::common
