#include "smart/record/schemas.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace smart::record {
namespace {

using ::testing::HasSubstr;

const std::string kSep = std::string(80, '=') + "\n";

TEST(Ros2msgDefinition, PoseArrayIsItsFieldsThenEachMessageItUsesOnce) {
  EXPECT_EQ(ros2msg_definition("geometry_msgs/msg/PoseArray"),
            "std_msgs/Header header\n"
            "geometry_msgs/Pose[] poses\n" +
                kSep + "MSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n" +
                kSep + "MSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n" + kSep +
                "MSG: geometry_msgs/Pose\ngeometry_msgs/Point position\n"
                "geometry_msgs/Quaternion orientation\n" +
                kSep + "MSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z\n" + kSep +
                "MSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w\n");
}

TEST(Ros2msgDefinition, MapsIdlTypesToMsgTypes) {
  const std::string idl = R"(
    // a comment with struct in it
    module p { module msg { module dds_ {
      @final struct Inner_ { boolean b; };
      @final struct All_ {
        long a; unsigned long b; long long c; unsigned long long d; short e;
        unsigned short f; float g; double h; string i; uint8 j; int8 k; octet l;
        sequence<double> m; double n[36]; sequence<p::msg::dds_::Inner_> o; Inner_ q;
      };
    }; }; };)";
  EXPECT_EQ(ros2msg_definition(idl, "p/msg/All"),
            "int32 a\nuint32 b\nint64 c\nuint64 d\nint16 e\nuint16 f\nfloat32 g\nfloat64 h\n"
            "string i\nuint8 j\nint8 k\nbyte l\nfloat64[] m\nfloat64[36] n\np/Inner[] o\n"
            "p/Inner q\n" +
                kSep + "MSG: p/Inner\nbool b\n");
}

TEST(Ros2msgDefinition, EveryRos2ViewTypeIsDefinedByTheIdl) {
  for (const char* t :
       {"geometry_msgs/msg/PoseArray", "geometry_msgs/msg/PoseStamped", "tf2_msgs/msg/TFMessage",
        "nav_msgs/msg/OccupancyGrid", "nav_msgs/msg/Path", "visualization_msgs/msg/MarkerArray"}) {
    EXPECT_FALSE(ros2msg_definition(t).empty()) << t;
  }
  EXPECT_THAT(ros2msg_definition("nav_msgs/msg/OccupancyGrid"), HasSubstr("int8[] data\n"));
}

TEST(Ros2msgDefinition, AnUnknownTypeIsNamed) {
  try {
    (void)ros2msg_definition("sensor_msgs/msg/Image");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("sensor_msgs/Image"));
    EXPECT_THAT(e.what(), HasSubstr("idl/ros2.idl"));
  }
}

TEST(SmartIdlText, IsTheWireDefinition) {
  EXPECT_THAT(std::string(smart_idl_text()), HasSubstr("@final struct RobotState {"));
  EXPECT_THAT(std::string(smart_idl_text()), HasSubstr("@final struct RunEvent {"));
  EXPECT_THAT(std::string(ros2_idl_text()), HasSubstr("module tf2_msgs"));
}

}  // namespace
}  // namespace smart::record
