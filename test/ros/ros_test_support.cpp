#include "ros_test_support.h"

#include <cv_bridge/cv_bridge.h>
#include <tf2_eigen/tf2_eigen.h>

#include "stocs/eval/pose_metrics.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/io/mesh_io.h"
#include "stocs_ros/common/cloud_conversion.h"
#include "stocs_ros/common/stamp_synchronizer.h"

namespace stocs_ros::test {

InputFrame loadInputFrame(const std::filesystem::path& dataset) {
  const stocs::BopDataset ds(dataset);
  const cv::Mat depth = ds.loadDepth(0, 0);
  const stocs::BopFrameCamera camera = ds.sceneCameras(0).at(0);
  InputFrame frame;
  frame.cloud = cloudToMsg(stocs::cloudFromDepth(depth, camera.intrinsics(depth.cols, depth.rows),
                                                 camera.depth_scale / 1000),
                           cv::Mat());
  frame.cloud.header.frame_id = "camera";
  frame.probability =
      *cv_bridge::CvImage(frame.cloud.header, "32FC1", ds.loadProbability(0, 0, 1)).toImageMsg();
  return frame;
}

std::map<std::string, uint64_t> statisticsCounts(const diagnostic_msgs::DiagnosticArray& msg) {
  std::map<std::string, uint64_t> counts;
  for (const diagnostic_msgs::DiagnosticStatus& s : msg.status) {
    for (const diagnostic_msgs::KeyValue& kv : s.values) counts[kv.key] = std::stoull(kv.value);
  }
  return counts;
}

uint64_t droppedMessages(std::map<std::string, uint64_t>& counts, const std::string& topic) {
  uint64_t dropped = 0;
  for (size_t r = 0; r < kDropReasonCount; ++r) {
    dropped += counts["dropped " + topic + ": " + shortName(static_cast<DropReason>(r))];
  }
  return dropped;
}

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

namespace {

/// `error` (ADD or ADD-S) of `pose` against `truth` over the vertices of the dataset's model of
/// `obj_id`, as a fraction of the model's diameter.
template <class Error>
double diameterRatio(const std::filesystem::path& dataset, int obj_id,
                     const Eigen::Isometry3d& pose, const Eigen::Isometry3d& truth, Error error) {
  const stocs::BopDataset ds(dataset);
  const stocs::MeshData model = stocs::loadMesh(ds.modelPath(obj_id).string(), 0.001f);
  const stocs::RigidPose estimate{pose.linear(), pose.translation()};
  return error(model.vertices, estimate, stocs::RigidPose{truth.linear(), truth.translation()}) /
         stocs::pointSetDiameter(model.vertices);
}

}  // namespace

double addsDiameterRatio(const std::filesystem::path& dataset, int obj_id,
                         const Eigen::Isometry3d& pose, const Eigen::Isometry3d& truth) {
  return diameterRatio(dataset, obj_id, pose, truth, stocs::addsError);
}

double addDiameterRatio(const std::filesystem::path& dataset, int obj_id,
                        const Eigen::Isometry3d& pose, const Eigen::Isometry3d& truth) {
  return diameterRatio(dataset, obj_id, pose, truth, stocs::addError);
}

int imageOf(const tf2_msgs::TFMessage& msg,
            const std::map<int, std::vector<stocs::BopGtInstance>>& gt) {
  for (const auto& [im, instances] : gt) {
    bool all = instances.size() == msg.transforms.size();
    for (size_t i = 0; i < instances.size() && all; ++i) {
      const geometry_msgs::Vector3& t = msg.transforms[i].transform.translation;
      all = std::abs(t.x - instances[i].t_mm.x() / 1000) < 1e-6 &&
            std::abs(t.y - instances[i].t_mm.y() / 1000) < 1e-6 &&
            std::abs(t.z - instances[i].t_mm.z() / 1000) < 1e-6;
    }
    if (all) return im;
  }
  return -1;
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
