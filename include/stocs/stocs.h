#pragma once
// stocs_ros for C++ programs outside ROS: prepare object models once, then estimate their 6D poses
// in depth frames from a segmentation network's per-object probability maps. Link stocs::core
// (`find_package(stocs)`; README, "Use from C++").
//
//   stocs::Estimator estimator;                           // defaults: docs/parameters.md
//   estimator.addObject("cat", "models/obj_000006.ply");  // in mm, as BOP models
//   stocs::Frame frame = stocs::Frame::fromDepth(depth_mm, camera, 0.001);
//   frame.probabilities["cat"] = probability;             // CV_32FC1 in [0, 1]
//   frame.colour = bgr;              // optional: CV_8UC3, registered with the depth image
//   for (const stocs::ObjectResult& r : estimator.estimate(frame))
//     if (r.estimate.found()) use(r.name, r.estimate.best().pose);  // model to camera, metres

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "stocs/estimation/frame.h"
#include "stocs/estimation/pipeline.h"
#include "stocs/model/model_cache.h"
#include "stocs/tracking/frame_tracker.h"
#include "stocs/tracking/stream_tracker.h"

namespace stocs {

class Estimator {
 public:
  /// Throws InputError naming the first parameter out of range.
  explicit Estimator(PipelineParams params = {}, ModelCache cache = ModelCache());

  /// Object `name` with the model in `model_file` (PLY, PCD, OBJ, STL, DAE, glTF or GLB, as
  /// loadMesh reads them; `unit_scale`: model units to metres), prepared once and cached. Throws
  /// InputError for a bad file or a name in use.
  void addObject(const std::string& name, const std::string& model_file, float unit_scale = 0.001f);
  /// Object `name` with a model prepared elsewhere, shared with its other users.
  void addObject(const std::string& name, std::shared_ptr<const PreparedModel> model);

  /// Every object added that `frame` has a probability map for, in the order they were added.
  std::vector<ObjectResult> estimate(const Frame& frame) const;
  /// Object `object` alone; throws InputError when it is unknown or the frame has no map for it.
  PoseEstimate estimate(const Frame& frame, const std::string& object) const;

  const PipelineParams& params() const { return params_; }
  /// The model of object `name`, or null.
  std::shared_ptr<const PreparedModel> model(const std::string& name) const;

 private:
  PipelineParams params_;
  ModelCache cache_;
  std::vector<std::pair<std::string, std::shared_ptr<const PreparedModel>>> objects_;
};

}  // namespace stocs
