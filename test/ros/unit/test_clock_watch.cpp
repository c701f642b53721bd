// The warning of a node waiting on simulated time whose /clock never comes: given only then, and
// saying how to get out of it.
#include <gtest/gtest.h>

#include "stocs_ros/common/clock_watch.h"

namespace stocs_ros {
namespace {

TEST(ClockWatch, WarnsOnlyOnSimulatedTimeWithoutAClockAfterItsPatience) {
  EXPECT_EQ(missingClockWarning("stocs", false, false, 60, 5), "") << "wall clock";
  EXPECT_EQ(missingClockWarning("stocs", true, true, 60, 5), "") << "the clock runs";
  EXPECT_EQ(missingClockWarning("stocs", true, false, 4.9, 5), "") << "still starting";
  const std::string w = missingClockWarning("scene_publisher", true, false, 5.02, 5);
  EXPECT_EQ(w.rfind("scene_publisher: /use_sim_time is true", 0), 0u) << w;
  EXPECT_NE(w.find("in 5 s"), std::string::npos) << w;
  EXPECT_NE(w.find("rosbag play --clock"), std::string::npos) << w;
  EXPECT_NE(w.find("rosparam set /use_sim_time false"), std::string::npos) << w;
}

}  // namespace
}  // namespace stocs_ros
