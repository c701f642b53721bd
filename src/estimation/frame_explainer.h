#pragma once
// The frame-level explanation (stages/frame_explanation.h) run on one frame's objects by
// estimateFrame and explainFrame, and the second search of an object whose every pose other
// objects' poses explain (estimation.explanation.search_again).

#include <map>
#include <vector>

#include "stocs/estimation/frame.h"
#include "stocs/estimation/stages/frame_explanation.h"

namespace stocs {

class FrameExplainer {
 public:
  FrameExplainer(const Frame& frame, const CameraIntrinsics& camera,
                 const std::vector<FrameObject>& objects, const PipelineParams& params);

  /// explainPoses over every instance of `estimates[i]`, the estimate of object i.
  std::vector<ExplainedPose> explain(const std::vector<PoseEstimate*>& estimates);
  std::vector<ExplainedPose> explain(std::vector<ObjectResult>& results);

  /// The objects, once each, that `explained` (the last explain()'s) left without an accepted
  /// pose while another object's pose explains one of theirs.
  std::vector<size_t> displaced(const std::vector<ExplainedPose>& explained) const;

  /// Object i searched for again (`estimate`) on its map without the surface that the accepted
  /// poses of the other objects confirm. Its new estimate is kept when, explained again with the
  /// others, it has an accepted pose; otherwise every pose is as before. Either way results[i]
  /// counts the time of both searches.
  void searchAgain(size_t i, const ObjectEstimator& estimate, std::vector<ObjectResult>& results);

 private:
  /// Every instance of `estimates` as a pose of the explanation.
  void collect(const std::vector<PoseEstimate*>& estimates);

  const Frame& frame_;
  const CameraIntrinsics& camera_;
  const std::vector<FrameObject>& objects_;
  const PipelineParams& params_;
  const FreeSpaceCheck visibility_;
  std::vector<const cv::Mat*> maps_;  ///< per object: its map, or the map it was searched on again
  std::map<size_t, cv::Mat> masked_;  ///< the maps objects were searched on again, by object
  std::vector<PoseEstimate*> estimates_;  ///< of the last collect()
  std::vector<FramePose> poses_;          ///< of the last collect()
  std::vector<size_t> owners_;            ///< per pose of poses_: its object's index
};

}  // namespace stocs
