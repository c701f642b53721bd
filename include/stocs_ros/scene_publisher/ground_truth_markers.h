#pragma once
// The scene publisher's ~ground_truth_markers: the played frame's ground-truth objects drawn as the
// node draws its estimates (bodyMarker: the config's mesh, else the model samples), in one
// translucent green, namespace gt_<object> and id k for instance k (TF frame gt_<object>_<k>).
// No labels: the node's labels name the estimates, and the green says truth. A point-drawn
// object's model is sampled on first use, as the node samples it (same file, unit and sampling
// parameters), so a publisher nobody watches in rviz prepares nothing.

#include <std_msgs/Header.h>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Geometry>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "stocs/model/object_model.h"
#include "stocs_ros/common/node_config.h"
#include "stocs_ros/common/object_markers.h"

namespace stocs_ros {

/// One ground-truth instance: object name, instance k (0: the first of its object in the frame)
/// and model-to-camera pose in metres.
struct TruthPose {
  std::string object;
  size_t instance = 0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

class GroundTruthMarkers {
 public:
  /// `config`: the estimator's configuration, whose objects, meshes and model sampling the
  /// markers follow; it must outlive this.
  explicit GroundTruthMarkers(const NodeConfig& config) : config_(config) {}

  /// The markers of one frame's truth, with `header` (the frame's frame_id and stamp), and DELETE
  /// markers for those of the previous call that are gone. Objects not in the config, and objects
  /// whose model cannot be read (logged once), are not drawn.
  visualization_msgs::MarkerArray build(const std::vector<TruthPose>& truth,
                                        const std_msgs::Header& header);

 private:
  /// The model samples of configured object `object`; empty for a mesh-drawn object.
  const stocs::ObjectModel& model(size_t object);

  const NodeConfig& config_;
  std::map<size_t, stocs::ObjectModel> models_;
  std::set<MarkerKey> shown_;
};

}  // namespace stocs_ros
