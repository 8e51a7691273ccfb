// The SMRC recording: states.csv in, compact frames out, poses back within one quantum.
#include "smart/serve/recording.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

namespace smart::serve {
namespace {

const char* kCsv =
    "t_s,robot,x_m,y_m,yaw_rad,v_mps,omega_radps,left_mps,right_mps,queue\n"
    "0,0,1,2,0,0,0,0,0,1\n"
    "0,1,5,2,3.14159,0,0,0,0,1\n"
    "0.5,0,1.25,2,0.5,0.5,0,0.5,0.5,300\n";  // robot 1 not reported: keeps its pose

TEST(Recording, RoundTripsPosesFrameByFrameAndCarriesMissingRobotsForward) {
  const auto rows = parse_states_csv(kCsv);
  ASSERT_EQ(rows.size(), 3u);
  const auto bytes = encode_recording(rows);
  EXPECT_EQ(bytes.substr(0, 4), "SMRC");
  EXPECT_EQ(bytes.size(), 40u + 2 * (4 + 2 * 7));
  const auto rec = decode_recording(bytes);
  ASSERT_EQ(rec.robots, 2u);
  ASSERT_EQ(rec.times_s, (std::vector<float>{0.0f, 0.5f}));
  const double q = 4.0 / 65535;            // extent 4 m
  EXPECT_NEAR(rec.poses[2].x_m, 1.25, q);  // frame 1, robot 0
  EXPECT_NEAR(rec.poses[2].yaw_rad, 0.5, 1e-4);
  EXPECT_NEAR(rec.poses[3].x_m, 5.0, q);  // frame 1, robot 1: carried forward
  EXPECT_NEAR(std::abs(rec.poses[1].yaw_rad), 3.14159, 1e-4);
  EXPECT_EQ(rec.poses[0].queue, 1u);
  EXPECT_EQ(rec.poses[2].queue, 255u);  // 300 saturates
  EXPECT_EQ(rec.poses[3].queue, 1u);    // carried forward with the pose
}

// Issue 25: a 16 KB results upload became a 668 MB recording (a few rows of a large fleet at many
// time stamps: every robot is in every frame).
TEST(Recording, ItsSizeIsKnownBeforehandAndBoundedByTheStatesItComesFrom) {
  const auto rows = parse_states_csv(kCsv);
  EXPECT_EQ(recording_bytes(rows), encode_recording(rows).size());
  EXPECT_NO_THROW(check_recording_size(rows, std::string(kCsv).size()));
  std::string forged = "t_s,robot,x_m,y_m,yaw_rad\n";
  for (int t = 0; t < 500; ++t) forged += std::to_string(t) + ",99999,1,1,0\n";
  const auto sparse = parse_states_csv(forged);
  EXPECT_EQ(recording_bytes(sparse), 40u + 500u * (4 + 100000u * 7));  // 350 MB
  try {
    check_recording_size(sparse, forged.size());
    FAIL() << "a " << forged.size() << "-byte states.csv was allowed a 350 MB recording";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("would make a recording of 333 MB"));
  }
}

TEST(Recording, BadInputIsAnErrorNamingWhatIsWrong) {
  EXPECT_THROW(decode_recording("SMRX"), std::invalid_argument);
  auto bytes = encode_recording(parse_states_csv(kCsv));
  bytes.pop_back();
  EXPECT_THROW(decode_recording(bytes), std::invalid_argument);
  try {
    parse_states_csv("header\n0,0,1,2,0\n0,zero,1,2,0\n");
    FAIL() << "a row with a word for a number was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("states.csv line 3"));
  }
  EXPECT_THROW(parse_states_csv("h\n0,0,nan,2,0\n"), std::invalid_argument);
}

TEST(PoseTail, KeepsTheNewestPosePerRobotFromPiecesOfAGrowingFile) {
  PoseTail tail;
  const std::string text = kCsv;
  tail.feed(text.substr(0, 80));  // the header and a piece of the first row
  EXPECT_TRUE(tail.latest().empty());
  tail.feed(text.substr(80));
  ASSERT_EQ(tail.latest().size(), 2u);
  EXPECT_DOUBLE_EQ(tail.latest()[0].x_m, 1.25);
  EXPECT_DOUBLE_EQ(tail.latest()[1].x_m, 5.0);
  EXPECT_DOUBLE_EQ(tail.time_s(), 0.5);
  tail.feed("0.6,1,oops\n1.0,1,6,2,0,0,0,0,0,0\n");  // a torn row is skipped
  EXPECT_DOUBLE_EQ(tail.latest()[1].x_m, 6.0);
  EXPECT_DOUBLE_EQ(tail.time_s(), 1.0);
}

// Issue 26: in an upload's live view every robot was blue; the live stream now says what each
// does, as the replay colours it.
TEST(PoseTail, ALiveRobotIsMovingWaitingOrIdleFromItsNewestState) {
  PoseTail tail;
  tail.feed(std::string(results::kStatesHeader) +
            "\n1.0,0,1,1,0,0.4,0,0.4,0.4,5\n1.0,1,2,2,0,0,0.5,0,0,3\n"
            "1.0,2,3,3,0,0.001,0.001,0,0,2\n1.0,3,4,4,0,0,0,0,0,0\n");
  ASSERT_EQ(tail.latest().size(), 4u);
  EXPECT_STREQ(live_status(tail.latest()[0]), "moving");   // driving
  EXPECT_STREQ(live_status(tail.latest()[1]), "moving");   // turning in place
  EXPECT_STREQ(live_status(tail.latest()[2]), "waiting");  // standing, 2 actions queued
  EXPECT_STREQ(live_status(tail.latest()[3]), "idle");     // standing, nothing queued
  EXPECT_EQ(tail.latest()[2].queue, 2u);
}

}  // namespace
}  // namespace smart::serve
