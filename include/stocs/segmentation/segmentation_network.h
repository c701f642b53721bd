#pragma once
// A segmentation network exported to ONNX, run on the CPU by OpenCV's DNN module: a colour image
// in, one probability map per output channel out, at the image's size.

#include <memory>
#include <opencv2/core/types.hpp>
#include <string>
#include <vector>

#include "stocs/segmentation/segmentation_network_params.h"

namespace cv {
class Mat;
}

namespace stocs {

class SegmentationNetwork {
 public:
  /// Loads and checks the model: throws InputError naming the file when it is missing or not a
  /// model OpenCV reads, or when a trial run on a blank image gives an output that is not NCHW
  /// with `params.classes` channels at the input size.
  explicit SegmentationNetwork(const SegmentationNetworkParams& params);
  ~SegmentationNetwork();
  SegmentationNetwork(SegmentationNetwork&&) noexcept;
  SegmentationNetwork& operator=(SegmentationNetwork&&) noexcept;

  /// Runs the network on a CV_8UC3 BGR image (OpenCV's order; `channel_order` says what the
  /// network wants): one CV_32FC1 map in [0, 1] per output channel, at the image's size. Throws
  /// InputError for an empty image or another type. Not for use from several threads at once.
  std::vector<cv::Mat> segment(const cv::Mat& bgr) const;

  /// The first half of segment(): the maps at the network's output resolution, as one
  /// CV_32FC<classes> image in [0, 1] of the part of the output that covers the image (letterbox
  /// padding cut off). Small: upsample() brings the channels a caller needs to the image's size.
  cv::Mat outputMaps(const cv::Mat& bgr) const;

  /// The channels `channels` of `maps` (outputMaps()), in that order, resized bilinearly to `size`
  /// into `out`: CV_32FC<n> probabilities for `depth` CV_32F, or CV_8UC<n> holding
  /// round(255 p) for CV_8U. `out` keeps its buffer when it already has that size and type (a
  /// view of a message's data), so the maps are written where they are sent from.
  static void upsample(const cv::Mat& maps, const std::vector<int>& channels, cv::Size size,
                       int depth, cv::Mat& out);

  const SegmentationNetworkParams& params() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stocs
