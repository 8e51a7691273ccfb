// serve/problem_folder.hpp: an uploaded LoRR folder's paths and the choice of its problem JSON.
#include "smart/serve/problem_folder.hpp"

#include <gtest/gtest.h>

namespace smart::serve {
namespace {

TEST(ProblemFolder, PlainRelativePathsAreAccepted) {
  EXPECT_EQ(check_folder_path("random.domain/maps/random-64-64-10.map"), "");
  EXPECT_EQ(check_folder_path("problem.json"), "");
  EXPECT_EQ(check_folder_path("a/b/c/d/e/f.txt"), "");
}

TEST(ProblemFolder, PathsThatCouldLeaveTheRunFolderAreRefusedNamingThem) {
  for (const char* bad : {"../etc/passwd", "a/../../b", "/abs/x.json", "a//b", "a/./b", "a\\b",
                          "..", "a/", "sp ace.map", "a/b/c/d/e/f/g.txt", ""}) {
    const auto why = check_folder_path(bad);
    EXPECT_NE(why, "") << bad;
    if (*bad != '\0') {
      EXPECT_NE(why.find(std::string(bad).substr(0, 3)), std::string::npos) << why;
    }
  }
  EXPECT_NE(check_folder_path(std::string(300, 'a')).find("longer than 255"), std::string::npos);
}

TEST(ProblemFolder, TheOnlyJsonAtTheTopIsTheProblemNotAnLsmartMapBelow) {
  const std::vector<std::string> paths{"w.domain/maps/w.json", "w.domain/p.json",
                                       "w.domain/agents/a.agents", "w.domain/tasks/t.tasks"};
  const auto c = choose_problem(paths, "");
  EXPECT_EQ(c.problem, "w.domain/p.json");
  EXPECT_EQ(c.error, "");
}

TEST(ProblemFolder, TwoProblemsNeedTheFormToNameOne) {
  const std::vector<std::string> paths{"d/a.json", "d/b.json", "d/maps/m.map"};
  const auto c = choose_problem(paths, "");
  EXPECT_EQ(c.problem, "");
  EXPECT_NE(c.error.find("2 problem JSON files (d/a.json, d/b.json)"), std::string::npos)
      << c.error;
  EXPECT_EQ(choose_problem(paths, "d/b.json").problem, "d/b.json");
  EXPECT_NE(choose_problem(paths, "d/maps/m.map").error.find("not a .json file"),
            std::string::npos);
  EXPECT_NE(choose_problem(paths, "d/c.json").error.find("d/c.json"), std::string::npos);
}

TEST(ProblemFolder, AFolderWithoutJsonSaysWhatItNeeds) {
  const auto c = choose_problem({"d/maps/m.map", "d/x.agents"}, "");
  EXPECT_NE(c.error.find("no problem JSON"), std::string::npos);
}

}  // namespace
}  // namespace smart::serve
