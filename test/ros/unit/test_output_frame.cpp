#include <gtest/gtest.h>

#include "stocs_ros/stocs_node/output_frame.h"

namespace stocs_ros {
namespace {

TEST(OutputFrame, MovesEveryPoseAndRotatesItsCovariance) {
  FrameResult result;
  result.header.frame_id = "camera";
  ObjectOutcome o;
  stocs::InstancePose instance;
  instance.pose.translation() = Eigen::Vector3f(0.1f, 0.2f, 0.8f);
  // Uncertain along the camera's z (depth) and about its x.
  instance.covariance.diagonal() << 1e-6, 1e-6, 4e-4, 9e-2, 1e-4, 1e-4;
  o.estimate.instances = {instance, instance};
  result.objects = {o};

  Eigen::Isometry3d base_from_camera = Eigen::Isometry3d::Identity();
  base_from_camera.translate(Eigen::Vector3d(1, 0, 0.5));
  base_from_camera.rotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));  // z -> -x
  moveResult(result, base_from_camera, "base_link");

  EXPECT_EQ(result.header.frame_id, "base_link");
  const stocs::PoseEstimate& e = result.objects[0].estimate;
  const Eigen::Vector3f expected = (base_from_camera.cast<float>() * instance.pose).translation();
  for (const stocs::InstancePose& moved : e.instances) {
    EXPECT_LT((moved.pose.translation() - expected).norm(), 1e-6);
    // The camera's z (depth) is base x now, and rotation about the camera's x is about base -z.
    EXPECT_NEAR(moved.covariance(0, 0), 4e-4, 1e-12);
    EXPECT_NEAR(moved.covariance(2, 2), 1e-6, 1e-12);
    EXPECT_NEAR(moved.covariance(5, 5), 9e-2, 1e-12);
    EXPECT_NEAR(moved.covariance(3, 3), 1e-4, 1e-12);
  }
}

}  // namespace
}  // namespace stocs_ros
