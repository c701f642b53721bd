#include "stocs/estimation/pose_estimate.h"

namespace stocs {

void PoseEstimate::takeFirstInstance() {
  found = !instances.empty();
  if (!found) return;
  const InstancePose& best = instances.front();
  pose = best.pose;
  score = best.score;
  lcp = best.lcp;
  refined = best.refined;
  region = best.region;
}

}  // namespace stocs
