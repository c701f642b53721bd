#pragma once
// The hard segment: the pixels whose probability exceeds a threshold, all with the same weight. The
// StoCS ablation and every baseline see the scene through it, built from the same organized cloud
// with the same voxel size and normals as the soft segment of StoCS.

#include <opencv2/core.hpp>

#include "stocs/estimation/stages/soft_segment.h"
#include "stocs/methods/pose_method.h"

namespace stocs {

/// 1 where `probability` (CV_32FC1) exceeds `threshold`, 0 elsewhere (NaN counts as 0).
cv::Mat hardProbability(const cv::Mat& probability, float threshold);

/// The segment parameters that keep exactly the pixels of a hardProbability() image.
SoftSegmentParams hardSegmentParams(SoftSegmentParams params);

/// The hard segment of the method input's probability image.
SoftSegment buildHardSegment(const ObjectInput& input, float threshold);

}  // namespace stocs
