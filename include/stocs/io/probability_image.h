#pragma once
// Per-pixel class probabilities from a segmentation network, as a CV_32FC1 image in [0, 1].

namespace cv {
class Mat;
}

namespace stocs {

/// Converts a network output image to probabilities: CV_32FC1 / CV_64FC1 as is, CV_16UC1 divided
/// by `uint16_scale` (10000 in the StoCS and BOP `prob/` format), CV_8UC1 divided by 255. Throws
/// InputError for other types, more than one channel, NaN, or values outside [0, 1] (with a
/// 1e-3 tolerance for rounding).
cv::Mat toProbabilityImage(const cv::Mat& image, double uint16_scale = 10000.0);

}  // namespace stocs
