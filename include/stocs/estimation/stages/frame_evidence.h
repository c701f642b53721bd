#pragma once
// What a frame says about a pose beyond the segment's shape: the measured surface (where the
// camera sees past the pose's surface) and the colour image. It tells a pose from its shape
// alternatives (StocsEstimator::search).

#include "stocs/estimation/stages/free_space_check.h"

namespace cv {
class Mat;
}

namespace stocs {

/// Any member may be null: that evidence is absent.
struct FrameEvidence {
  const FreeSpaceCheck* surface = nullptr;
  const cv::Mat* colour = nullptr;  ///< CV_8UC3 BGR registered with the cloud (colourAgreement)
};

}  // namespace stocs
