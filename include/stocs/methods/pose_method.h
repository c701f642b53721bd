#pragma once
// A pose estimation method run on one object in one frame (ObjectInput to PoseEstimate), so that
// StoCS, its ablations and the baselines are compared on exactly the same inputs
// (`stocs estimate --method`, `stocs bench`).

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "stocs/estimation/frame.h"
#include "stocs/estimation/pipeline.h"
#include "stocs/model/model_cache.h"

namespace stocs {

struct MethodOptions {
  /// Probability threshold that turns the soft segmentation into the hard segment given to the
  /// methods that need one (the paper's best value for its baselines).
  float hard_threshold = 0.4f;
};

class PoseMethod {
 public:
  virtual ~PoseMethod() = default;
  virtual std::string name() const = 0;
  /// Builds the per-model state a method keeps (e.g. a trained detector) ahead of estimate(), so
  /// that this offline step stays out of the timings, as the PPF map of StoCS is prepared before
  /// the clock starts. Optional: estimate() builds what is missing itself.
  virtual void prepare(const PreparedModel& /*model*/) {}
  /// Whether the method's poses carry a calibrated confidence and verdict (InstancePose::
  /// confidence, accepted); a method without one is judged by its own score.
  virtual bool givesConfidence() const { return false; }
  /// Not const: a method may keep per-model state (e.g. a trained detector) between frames.
  virtual PoseEstimate estimate(const ObjectInput& input) = 0;
};

using MethodFactory = std::function<std::unique_ptr<PoseMethod>(const MethodOptions&)>;

/// Adds a method to those `makeMethod` knows, or replaces the one of that name: methods of a
/// library the others do not link (e.g. the Open3D baselines, open3d_methods.h) are added by the
/// program that links it, before it parses its options. Not thread-safe.
void registerMethod(const std::string& name, MethodFactory factory);

/// Names `makeMethod` accepts.
std::vector<std::string> methodNames();

/// A method by name; throws InputError naming the unknown method and listing the known ones.
std::unique_ptr<PoseMethod> makeMethod(const std::string& name, const MethodOptions& options = {});

}  // namespace stocs
