#include "stocs/estimation/pose_estimate.h"

namespace stocs {

void PoseEstimate::setFound() {
  found = !instances.empty();
}

}  // namespace stocs
