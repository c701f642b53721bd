// Labels of neighbouring objects: overlapping ones are moved up until none overlap, as a camera at
// the frame's origin sees them; others stay where they are.
#include <gtest/gtest.h>

#include "stocs_ros/common/object_markers.h"

namespace stocs_ros {
namespace {

visualization_msgs::Marker label(const std::string& text, double x, double y, double z) {
  visualization_msgs::Marker m;
  m.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
  m.text = text;
  m.scale.z = 0.03;
  m.pose.position.x = x;
  m.pose.position.y = y;
  m.pose.position.z = z;
  return m;
}

/// Whether the image boxes of two labels overlap (kLabelCharWidth text heights per character).
bool overlap(const visualization_msgs::Marker& a, const visualization_msgs::Marker& b) {
  const auto box = [](const visualization_msgs::Marker& m) {
    const double z = m.pose.position.z, h = m.scale.z / z;
    return std::array<double, 4>{m.pose.position.x / z, m.pose.position.y / z,
                                 kLabelCharWidth * h * static_cast<double>(m.text.size()) / 2,
                                 h / 2};
  };
  const auto p = box(a), q = box(b);
  return std::abs(p[0] - q[0]) < p[2] + q[2] - 1e-9 && std::abs(p[1] - q[1]) < p[3] + q[3] - 1e-9;
}

TEST(ObjectMarkers, OverlappingLabelsAreMovedUpUntilNoneOverlap) {
  visualization_msgs::MarkerArray markers;
  // Three labels side by side at about one height (in the image, the middle one lowest), and one
  // far away.
  markers.markers = {label("box 0.403", 0.02, -0.051, 0.8),
                     label("cylinder 0.379", 0.1, -0.05, 0.8),
                     label("mug 0.282", -0.02, -0.047, 0.75), label("bowl 0.290", -0.2, 0.1, 0.7)};
  visualization_msgs::Marker body;
  body.type = visualization_msgs::Marker::POINTS;
  markers.markers.push_back(body);
  const visualization_msgs::MarkerArray before = markers;
  for (size_t i = 0; i + 1 < 3; ++i) ASSERT_TRUE(overlap(before.markers[i], before.markers[i + 1]));

  separateOverlappingLabels(markers);
  for (size_t i = 0; i < 4; ++i) {
    for (size_t j = i + 1; j < 4; ++j) {
      EXPECT_FALSE(overlap(markers.markers[i], markers.markers[j]))
          << markers.markers[i].text << " / " << markers.markers[j].text;
    }
    // Only up (-y), never sideways or in depth.
    EXPECT_LE(markers.markers[i].pose.position.y, before.markers[i].pose.position.y);
    EXPECT_EQ(markers.markers[i].pose.position.x, before.markers[i].pose.position.x);
    EXPECT_EQ(markers.markers[i].pose.position.z, before.markers[i].pose.position.z);
  }
  // The lowest label (cylinder) and the one far away stay; the others rise by a little more than
  // a text height per label below them at most.
  EXPECT_EQ(markers.markers[1].pose, before.markers[1].pose);
  EXPECT_EQ(markers.markers[3].pose, before.markers[3].pose);
  for (size_t i : {0, 2}) {
    EXPECT_LT(markers.markers[i].pose.position.y, before.markers[i].pose.position.y);
    EXPECT_GT(markers.markers[i].pose.position.y, before.markers[i].pose.position.y - 3 * 0.03);
  }
  EXPECT_EQ(markers.markers[4], body);
}

TEST(ObjectMarkers, LabelsMovedOntoTheEdgeOfAnotherAreSeparatedToo) {
  // Once moved just above the first, rounding left this second label overlapping it by a hair,
  // and it was moved to the same place again, forever (the node's worker hung).
  visualization_msgs::MarkerArray markers;
  markers.markers = {
      label("mug 0.282", -0.06281874682105645, 0.09850868243521302, 0.9439786115181159),
      label("cylinder 0.379", 0.048629332084499544, 0.07911507892829836, 0.9893009028172247)};
  for (visualization_msgs::Marker& m : markers.markers) m.scale.z = 0.025;
  ASSERT_TRUE(overlap(markers.markers[0], markers.markers[1]));
  separateOverlappingLabels(markers);
  EXPECT_FALSE(overlap(markers.markers[0], markers.markers[1]));
}

}  // namespace
}  // namespace stocs_ros
