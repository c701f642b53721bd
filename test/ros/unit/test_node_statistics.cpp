// The node's counters: every message and frame lands in exactly one published count, rejections
// are keyed by the input at fault, and the level warns once per new problem.
#include <gtest/gtest.h>

#include <map>
#include <stdexcept>

#include "stocs/util/error.h"
#include "stocs_ros/stocs_node/node_statistics.h"

namespace stocs_ros {
namespace {

std::map<std::string, std::string> values(const diagnostic_msgs::DiagnosticStatus& status) {
  std::map<std::string, std::string> out;
  for (const diagnostic_msgs::KeyValue& kv : status.values) out[kv.key] = kv.value;
  return out;
}

TEST(NodeStatistics, CountsEveryMessageAndFrameOnce) {
  NodeStatistics stats({"/cloud", "/probability/box"});
  for (int k = 0; k < 5; ++k) stats.received(0);
  for (int k = 0; k < 4; ++k) stats.received(1);
  stats.dropped(
      {{0, ros::Time(1), DropReason::kUnmatched}, {1, ros::Time(2), DropReason::kTooOld}});
  for (int k = 0; k < 3; ++k) stats.matched();
  stats.estimated();
  stats.replaced();
  stats.serviceCall(true);
  stats.serviceCall(false);
  stats.timeJumpedBack();

  std::map<std::string, std::string> v = values(stats.status("/stocs", {1, 0}));
  EXPECT_EQ(v["received /cloud"], "5");
  EXPECT_EQ(v["received /probability/box"], "4");
  EXPECT_EQ(v["dropped /cloud: unmatched"], "1");
  EXPECT_EQ(v["dropped /cloud: too old"], "0");
  EXPECT_EQ(v["dropped /probability/box: too old"], "1");
  EXPECT_EQ(v["queued /cloud"], "1");
  EXPECT_EQ(v["frames matched"], "3");
  EXPECT_EQ(v["frames estimated"], "1");
  EXPECT_EQ(v["frames replaced"], "1");
  EXPECT_EQ(v["frames in progress"], "1");
  EXPECT_EQ(v["service calls"], "2");
  EXPECT_EQ(v["service calls failed"], "1");
  EXPECT_EQ(v["time jumps back"], "1");

  stats.rejected("cloud");
  v = values(stats.status("/stocs", {1, 0}));
  EXPECT_EQ(v["frames rejected"], "1");
  EXPECT_EQ(v["frames rejected: cloud"], "1");
  EXPECT_EQ(v["frames in progress"], "0");
  EXPECT_NE(stats.summary().find("3 frames matched: 1 estimated, 1 replaced by a newer frame, 1 "
                                 "rejected, 0 kept for ~estimate, 0 in progress"),
            std::string::npos)
      << stats.summary();
  EXPECT_NE(stats.summary().find("/cloud: 5 received, dropped 1 unmatched"), std::string::npos)
      << stats.summary();
  EXPECT_NE(stats.summary().find("time went back 1 times"), std::string::npos) << stats.summary();
}

TEST(NodeStatistics, CountsTrackedRedetectedLostAndHiddenPoses) {
  NodeStatistics stats({"/cloud"});
  stocs::TrackingCounts first;
  first.redetected = 2;
  first.detections = 2;
  stocs::TrackingCounts next;
  next.tracked = 1;
  next.lost = 1;
  next.hidden = 2;
  next.detections = 1;
  next.reset = true;
  stats.tracking(first);
  stats.tracking(next);
  std::map<std::string, std::string> v = values(stats.status("/stocs", {0}));
  EXPECT_EQ(v["poses tracked"], "1");
  EXPECT_EQ(v["poses redetected"], "2");
  EXPECT_EQ(v["poses lost"], "1");
  EXPECT_EQ(v["poses hidden"], "2");
  EXPECT_EQ(v["full detections while tracking"], "3");
  EXPECT_EQ(v["tracking resets"], "1");
  EXPECT_NE(stats.summary().find("tracking: 1 tracked, 2 redetected, 1 lost, 2 hidden, 3 full "
                                 "detections, 1 resets"),
            std::string::npos)
      << stats.summary();
}

TEST(NodeStatistics, WarnsOncePerNewProblem) {
  NodeStatistics stats({"/cloud"});
  EXPECT_EQ(stats.status("n", {0}).level, diagnostic_msgs::DiagnosticStatus::OK);
  stats.dropped({{0, ros::Time(1), DropReason::kLate}});
  EXPECT_EQ(stats.status("n", {0}).level, diagnostic_msgs::DiagnosticStatus::WARN);
  EXPECT_EQ(stats.status("n", {0}).level, diagnostic_msgs::DiagnosticStatus::OK);
  stats.matched();
  stats.rejected("cloud");
  EXPECT_EQ(stats.status("n", {0}).level, diagnostic_msgs::DiagnosticStatus::WARN);
}

TEST(NodeStatistics, RejectionKindIsTheInputTheErrorNames) {
  const auto kind = [](auto error) { return rejectionKind(std::make_exception_ptr(error)); };
  EXPECT_EQ(kind(stocs::InputError("cloud: cloud is not organized (height 1)")), "cloud");
  EXPECT_EQ(kind(stocs::InputError("probability image of 'box': image is empty (0x0)")),
            "probability image of 'box'");
  EXPECT_EQ(kind(stocs::InputError("no prefix")), "no prefix");
  EXPECT_EQ(kind(std::runtime_error("cloud: bug")), "internal error");
}

}  // namespace
}  // namespace stocs_ros
