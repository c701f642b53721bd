#pragma once
// Pixel precision and recall of a probability map thresholded into a hard segment, against a mask.

namespace cv {
class Mat;
}

namespace stocs {

struct PixelCounts {
  long true_positive = 0;
  long false_positive = 0;
  long false_negative = 0;

  /// Share of the segment that is on the mask (1 for an empty segment).
  double precision() const;
  /// Share of the mask that is in the segment (1 for an empty mask).
  double recall() const;
  PixelCounts& operator+=(const PixelCounts& other);
};

/// Counts the pixels of `probability` (CV_32FC1) above `threshold` against `mask` (CV_8UC1,
/// non-zero on the object). Throws InputError when the types or sizes differ.
PixelCounts countSegmentPixels(const cv::Mat& probability, const cv::Mat& mask, float threshold);

}  // namespace stocs
