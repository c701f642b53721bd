#include "stocs_ros/stocs_node/output_publisher.h"

#include <tf2_eigen/tf2_eigen.h>

#include "stocs_ros/stocs_node/result_messages.h"

namespace stocs_ros {

OutputPublisher::OutputPublisher(ros::NodeHandle& pnh)
    : pnh_(pnh),
      poses_(pnh.advertise<geometry_msgs::PoseArray>("poses", 1)),
      objects_(pnh.advertise<ObjectPoseArray>("objects", 1)),
      markers_(pnh.advertise<visualization_msgs::MarkerArray>("markers", 1)) {}

void OutputPublisher::publish(const FrameResult& result, const EstimationSetup& setup,
                              uint64_t timeline) {
  if (timeline < timeline_) return;
  if (timeline > timeline_) {
    timeline_ = timeline;
    newest_stamp_.reset();
    tf_stamps_.clear();
  }
  if (newest_stamp_ && result.header.stamp < *newest_stamp_) return;
  newest_stamp_ = result.header.stamp;
  const OutputConfig& output = setup.config.output;
  if (output.tf) publishTransforms(result, setup);
  poses_.publish(toPoseArray(result));
  objects_.publish(toObjectPoseArray(result, setup));
  if (output.markers) markers_.publish(toMarkers(result, setup, shown_markers_));
  publishPerObject(result, setup);
}

void OutputPublisher::publishPerObject(const FrameResult& result, const EstimationSetup& setup) {
  for (const FoundPose& f : foundPoses(result)) {
    const std::string name = instanceName(setup.config.objects[f.outcome->object].name, f.instance);
    auto publisher = per_object_.find(name);
    if (publisher == per_object_.end()) {
      publisher = per_object_
                      .emplace(name, pnh_.advertise<geometry_msgs::PoseWithCovarianceStamped>(
                                         "pose/" + name, 1))
                      .first;
    }
    if (publisher->second.getNumSubscribers() > 0) {
      publisher->second.publish(toPoseWithCovariance(f, result, setup));
    }
  }
}

void OutputPublisher::publishTransforms(const FrameResult& result, const EstimationSetup& setup) {
  std::vector<geometry_msgs::TransformStamped> transforms;
  for (const FoundPose& f : foundPoses(result)) {
    const std::string child =
        setup.config.output.frame_prefix +
        instanceName(setup.config.objects[f.outcome->object].name, f.instance);
    const auto last = tf_stamps_.find(child);
    if (last != tf_stamps_.end() && result.header.stamp <= last->second) continue;
    geometry_msgs::TransformStamped t =
        tf2::eigenToTransform(Eigen::Isometry3d(f.estimate.pose.cast<double>()));
    t.header = result.header;
    t.child_frame_id = child;
    transforms.push_back(t);
    tf_stamps_[child] = result.header.stamp;
  }
  if (!transforms.empty()) tf_.sendTransform(transforms);
}

}  // namespace stocs_ros
