// Input problems as the user reads them (smart/grid/problem.hpp): each names its file, line and
// robot; many of one kind get a line saying so first (issue 26: a plan of another instance
// listed 247 problems and no summary).
#include "smart/grid/problem.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace smart::grid {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

TEST(InputError, NamesFileLineAndRobotOfEachProblem) {
  const InputError e({{"p.txt", 3, 1, "step 2 is off the map"}, {"m.map", 0, -1, "no map line"}});
  EXPECT_EQ(std::string(e.what()), "p.txt:3: robot 1: step 2 is off the map\nm.map: no map line");
}

TEST(InputError, ManyProblemsOfOneKindAreSaidToBeOneMistakeFirst) {
  std::vector<Problem> ps;
  for (int r = 0; r < 30; ++r) {
    ps.push_back({"p.txt", r + 1, r,
                  "step " + std::to_string(r) + " is (x=" + std::to_string(20 + r) +
                      ",y=1), outside the 8x8 map"});
  }
  ps.push_back({"p.txt", 40, 3, "robot 3 waits forever"});
  const std::string what = InputError(ps).what();
  EXPECT_THAT(what, StartsWith("30 of 31 problems are one kind, most likely one mistake: step # is "
                               "(x=#,y=#), outside the #x# map\n"));
  EXPECT_THAT(what, HasSubstr("\np.txt:40: robot 3: robot 3 waits forever"));  // all listed
  ps.resize(9);  // few: listed as they are
  EXPECT_THAT(std::string(InputError(ps).what()), StartsWith("p.txt:1: robot 0: step 0"));
}

}  // namespace
}  // namespace smart::grid
