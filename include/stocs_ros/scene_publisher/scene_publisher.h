#pragma once
// Plays a BOP dataset as ROS sensor topics at a fixed rate (a generated or real sequence's own,
// from scene_events.json, unless ~rate says otherwise), frames in scene then image id order: the
// organized cloud, the depth image with camera_info, the colour image, per-object probability
// images (or one multi-channel image, as the estimator's config says; the dataset's prob/ maps or
// simulated ones, as ~probability_source says), the boundary map, and the ground truth as TF frames
// gt_<object> and, while someone subscribes, as rviz markers (ground_truth_markers.h). Every
// message of one frame carries the same stamp: the time it is published, taken once all of them are
// built, so that latencies measured from it (scripts/bench_latency.sh) are those of the receiver
// and not of this player's own conversions. Each frame is read from disk (mostly PNG decoding) in
// a thread of its own while the one before is published and the timer waits, so that reading
// does not add to the time between frames; with ~cache each frame is decoded once and kept, and
// ~preload decodes every frame before the first is published, so that a loop (and, with
// ~preload, every pass) sustains rates the decoding alone would not.

#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include <functional>
#include <future>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "stocs/io/bop_dataset.h"
#include "stocs/sim/probability_source.h"
#include "stocs/sim/segmentation_input_source.h"
#include "stocs_ros/common/clock_watch.h"
#include "stocs_ros/common/node_config.h"
#include "stocs_ros/scene_publisher/bop_frame.h"
#include "stocs_ros/scene_publisher/ground_truth_markers.h"
#include "stocs_ros/scene_publisher/scene_publisher_params.h"

namespace stocs_ros {

class ScenePublisher {
 public:
  /// Reads the private parameters (docs/ros.md, "Scene publisher") and starts the timer. Throws
  /// stocs::InputError for a bad parameter, dataset or config.
  explicit ScenePublisher(ros::NodeHandle pnh);

 private:
  struct FrameRef {
    int scene;
    int image;
  };

  /// Publishes the frame loaded since the last tick and starts loading the next.
  void onTimer(const ros::TimerEvent&);
  /// Starts loading the next frame in a thread of its own (none after the last without ~loop),
  /// or takes it from the cache.
  void loadNext();
  /// Reads frame `index` of frames_ (kept in the cache with ~cache).
  std::shared_ptr<const BopFrame> load(size_t index);
  /// ~preload: every frame into the cache before the first is published.
  void preload();
  /// Sets the stamp of a built message and publishes it.
  using Send = std::function<void(const ros::Time& stamp)>;

  void publish(const FrameRef& ref, const BopFrame& frame);
  void addProbabilities(const BopFrame& frame, const std_msgs::Header& header,
                        std::vector<Send>& sends);
  /// input.probability labels, masks or boxes: checks ~probability_source and advertises the
  /// form's topic.
  void advertiseSegmentation();
  /// The frame's labels, masks or boxes from ~probability_source.
  void addSegmentation(const FrameRef& ref, const std_msgs::Header& header,
                       std::vector<Send>& sends);
  void publishGroundTruth(const FrameRef& ref, const std_msgs::Header& header);
  /// Warns, once, of an object in a frame's ground truth that the frame has no map for.
  void warnOfMissingMap(const FrameRef& ref, const BopFrame& frame);
  /// Whether the object may be in the frame: its ground truth has it, or the scene has none.
  bool mayShow(const FrameRef& ref, int obj_id) const;
  std::string objectName(int obj_id) const;

  ros::NodeHandle pnh_;
  ScenePublisherParams params_;
  stocs::BopDataset dataset_;
  NodeConfig config_;  ///< the estimator's config: object names and ids, probability form
  std::unique_ptr<stocs::ProbabilitySource> probability_source_;  ///< ~probability
  /// input.probability labels, masks or boxes: their source (~probability_source), used from the
  /// timer's thread only, and each configured object's class id by object id.
  std::unique_ptr<stocs::SegmentationInputSource> segmentation_;
  std::map<int, int> class_of_;
  bool warned_of_missing_map_ = false;
  std::vector<int> object_ids_;
  std::vector<FrameRef> frames_;
  size_t next_ = 0;
  int pass_ = 1;  ///< passes over the frames so far, this one included (more with ~loop)
  std::map<int, std::map<int, stocs::BopFrameCamera>> cameras_;  // by scene, image
  std::map<int, std::map<int, std::vector<stocs::BopGtInstance>>> ground_truth_;

  ros::Publisher cloud_, depth_, camera_info_, rgb_, multichannel_, boundary_, segmentation_pub_;
  std::vector<ros::Publisher> probabilities_;  // per object, input.probability: per_object
  tf2_ros::TransformBroadcaster tf_;
  ros::Publisher truth_markers_;
  GroundTruthMarkers truth_marker_builder_{config_};
  ros::Timer timer_;
  /// The timer above waits for ROS time: a warning when /use_sim_time is on and no /clock comes.
  ClockWatch clock_watch_{pnh_, "scene_publisher"};
  /// The frame being loaded; last, so that it is waited for before anything it uses goes.
  /// ~cache: decoded frames by index into frames_ (null: not read yet); written by the loading
  /// thread, one load at a time, and read before the next load starts.
  std::vector<std::shared_ptr<const BopFrame>> cache_;
  bool cache_frames_ = false;
  FrameRef pending_ref_{};
  std::future<std::shared_ptr<const BopFrame>> pending_;
};

}  // namespace stocs_ros
