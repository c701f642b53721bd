#pragma once

#include "stocs/methods/pose_method.h"

namespace stocs {

/// StoCS on the soft segmentation (the package's method).
class StocsMethod : public PoseMethod {
 public:
  std::string name() const override { return "stocs"; }
  bool givesConfidence() const override { return true; }
  PoseEstimate estimate(const ObjectInput& input) override;
};

/// Ablation: StoCS on the hard segment (probability above a threshold, uniform weights).
class HardSegmentStocsMethod : public PoseMethod {
 public:
  explicit HardSegmentStocsMethod(float threshold) : threshold_(threshold) {}
  std::string name() const override { return "stocs-hard"; }
  bool givesConfidence() const override { return true; }
  PoseEstimate estimate(const ObjectInput& input) override;

 private:
  float threshold_;
};

}  // namespace stocs
