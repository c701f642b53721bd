#include "ros_test_support.h"

#include <tf2_eigen/tf2_eigen.h>

#include "stocs/bop_dataset.h"
#include "stocs/mesh.h"
#include "stocs/pose_metrics.h"

namespace stocs_ros::test {

Eigen::Isometry3d groundTruthPose(const std::filesystem::path& dataset, int scene, int image,
                                  int obj_id) {
  const auto ground_truth = stocs::BopDataset(dataset).sceneGroundTruth(scene);
  for (const stocs::BopGtInstance& g : ground_truth.at(image)) {
    if (g.obj_id != obj_id) continue;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = g.R;
    pose.translation() = g.t_mm / 1000.0;
    return pose;
  }
  ADD_FAILURE() << dataset.string() << ": no ground truth for object " << obj_id;
  return Eigen::Isometry3d::Identity();
}

double addsDiameterRatio(const std::filesystem::path& dataset, int obj_id,
                         const Eigen::Isometry3d& pose, const Eigen::Isometry3d& truth) {
  const stocs::BopDataset ds(dataset);
  const stocs::MeshData model = stocs::loadMesh(ds.modelPath(obj_id).string(), 0.001f);
  const stocs::RigidPose estimate{pose.linear(), pose.translation()};
  const double error =
      stocs::addsError(model.vertices, estimate, {truth.linear(), truth.translation()});
  return error / stocs::pointSetDiameter(model.vertices);
}

Eigen::Isometry3d poseToEigen(const geometry_msgs::Pose& pose) {
  Eigen::Isometry3d out;
  tf2::fromMsg(pose, out);
  return out;
}

double translationError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm();
}

double rotationError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  // Through the quaternion: acos of the trace loses precision near zero.
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
}

}  // namespace stocs_ros::test
