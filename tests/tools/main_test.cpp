// Exit codes of the `smart` executable as the README documents them, and the error printer's
// messages (a real process; stderr captured through /bin/sh).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "support/smart_process.hpp"

namespace smart::tools {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

test::SmartRun smart_with_stderr(const std::string& args, const std::string& tag) {
  const auto out = test::temp_file(tag + ".out");
  common::ChildProcess p({"/bin/sh", "-c", test::smart_exe().string() + " " + args + " 2>&1"}, out);
  test::SmartRun r;
  r.code = p.wait(60s).value_or(-1);
  r.out = test::slurp(out);
  std::filesystem::remove(out);
  return r;
}

TEST(SmartMain, HelpIsSuccess) {
  const auto r = smart_with_stderr("run --help", "help");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_THAT(r.out, HasSubstr("--clock"));
  EXPECT_THAT(r.out, HasSubstr("lockstep|realtime"));
}

// CLI11's help: a heading line ends in ':'; an option line starts "  -", its text from column 30
// or on the next line, indented 30.
struct HelpPage {
  std::vector<std::string> subcommands, headings, undescribed;
};
HelpPage read_help(const std::string& text) {
  HelpPage page;
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  std::string heading;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto& l = lines[i];
    if (!l.empty() && l[0] != ' ' && l.back() == ':') {
      heading = l;
      page.headings.push_back(l);
    } else if (heading == "Subcommands:" && l.size() > 2 && l[2] != ' ') {
      page.subcommands.push_back(l.substr(2, l.find(' ', 2) - 2));
    } else if (l.rfind("  -", 0) == 0) {
      const bool inline_text = l.size() > 30 && l.substr(28, 2) == "  " && l[30] != ' ';
      const bool next_text =
          i + 1 < lines.size() && lines[i + 1].rfind(std::string(30, ' '), 0) == 0;
      if (!inline_text && !next_text) page.undescribed.push_back(l);
    }
  }
  return page;
}

// Issue 26: options without help text, and `run --help` as 69 flat lines.
TEST(SmartMain, EveryOptionOfEveryCommandSaysWhatItDoesAndRunsHelpIsGrouped) {
  std::vector<std::string> todo{""};
  std::size_t pages = 0;
  while (!todo.empty()) {
    const std::string command = todo.back();
    todo.pop_back();
    const auto r = smart_with_stderr(command + " --help", "help_walk");
    ASSERT_EQ(r.code, 0) << command << ": " << r.out;
    const auto page = read_help(r.out);
    ++pages;
    EXPECT_THAT(page.undescribed, ::testing::IsEmpty()) << "smart " << command << " --help";
    for (const auto& sub : page.subcommands)
      todo.push_back(command + (command.empty() ? "" : " ") + sub);
  }
  EXPECT_GT(pages, 25u);  // every command and sub-command was read
  const auto run = read_help(smart_with_stderr("run --help", "help_run").out);
  for (const char* heading : {"Problem:", "Robots and execution uncertainty:",
                              "Network, DDS and trust:", "Run control:", "Outputs:", "Sim host:"}) {
    EXPECT_THAT(run.headings, ::testing::Contains(heading));
  }
}

// Issue 26: no `--version`, and a typo said only "A subcommand is required".
TEST(SmartMain, VersionAndAMistypedCommandSayWhatTheyShould) {
  const auto v = smart_with_stderr("--version", "version");
  EXPECT_EQ(v.code, 0);
  EXPECT_THAT(v.out, ::testing::ContainsRegex("^smart [0-9]+\\.[0-9]+\\.[0-9]+ \\(Cyclone DDS "
                                              "0\\.10\\.[0-9]+\\)"));
  const auto typo = smart_with_stderr("--log-level warn rnu --map x", "typo");
  EXPECT_EQ(typo.code, 2);
  EXPECT_THAT(typo.out, HasSubstr("'rnu' is not a smart command; did you mean 'run'?"));
  const auto far = smart_with_stderr("xyzzy", "unknown");
  EXPECT_EQ(far.code, 2);
  EXPECT_THAT(far.out, HasSubstr("'xyzzy' is not a smart command (`smart --help` lists them)"));
}

TEST(SmartMain, CommandLineErrorsAreBadInput) {
  auto r = smart_with_stderr("run --map a.map --scen a.scen --plan p --clock sometimes", "clock");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_THAT(r.out, HasSubstr("'sometimes' is not one of lockstep|realtime"));
  r = smart_with_stderr("check-plan --map a.map", "missing");
  EXPECT_EQ(r.code, 2) << r.out;
  r = smart_with_stderr("no-such-command", "unknown");
  EXPECT_EQ(r.code, 2) << r.out;
}

// Regression: `smart agent --period-s 0` busy-looped at 100 % CPU.
TEST(SmartMain, AZeroControlPeriodIsBadInput) {
  const auto r = smart_with_stderr("agent --robot-id 0 --period-s 0", "period");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_THAT(r.out, HasSubstr("'0' is not a number from 0.005 to 10"));
}

TEST(SmartMain, MissingFilesAndConfigAreBadInput) {
  auto r = smart_with_stderr("sim --map /nonexistent.map --scen x.scen", "nomap");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_THAT(r.out, HasSubstr("/nonexistent.map"));
  r = smart_with_stderr("agent --robot-id 0 --config no-such-robot", "norobot");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_THAT(r.out, HasSubstr("no-such-robot"));
}

TEST(SmartMain, AnI2cBusThatCannotBeOpenedIsASystemFailure) {
  const auto r =
      smart_with_stderr("agent --robot-id 0 --i2c /nonexistent/i2c-9 --vicon-port 0 --domain " +
                            std::to_string(test::kAgentI2cMissing),
                        "i2c");
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_THAT(r.out, HasSubstr("I2C error"));
  EXPECT_THAT(r.out, HasSubstr("/nonexistent/i2c-9"));
}

}  // namespace
}  // namespace smart::tools
