#pragma once
// Parameters of running a segmentation network exported to ONNX (SegmentationNetwork): how a
// colour image becomes the network's input and how its output becomes per-object probabilities.

#include <string>
#include <vector>

#include "stocs/util/param_set.h"

namespace stocs {

struct SegmentationNetworkParams {
  enum class Resize { kStretch, kLetterbox };
  enum class ChannelOrder { kRgb, kBgr };
  enum class Output { kLogits, kProbabilities };
  enum class Activation { kSoftmax, kSigmoid };

  /// The ONNX file; empty: none (the node refuses to start, the CLI names the problem).
  std::string model;
  /// The network's input size; images are resized to it and the maps back to the image's size.
  int input_width = 160;
  int input_height = 120;
  /// kStretch: to the input size whatever the aspect; kLetterbox: keep the aspect, pad with zero.
  Resize resize = Resize::kStretch;
  ChannelOrder channel_order = ChannelOrder::kRgb;
  /// The input is (pixel - mean) * scale per channel, mean in the pixel's 0-255 units, in the
  /// order of the channel_order (as cv::dnn::blobFromImage).
  float mean_0 = 0, mean_1 = 0, mean_2 = 0;
  float scale = 1.0f / 255.0f;
  /// What the single NCHW output holds: logits (the activation turns them into probabilities)
  /// or probabilities already.
  Output output = Output::kLogits;
  /// Softmax over the channels (one class per pixel) or a sigmoid per channel (independent ones).
  Activation activation = Activation::kSoftmax;
  /// The number of output channels the model must have.
  int classes = 7;
  /// The object of each output channel in order ("-": none, as the background); empty: channel k
  /// is the object named k (a BOP obj_id).
  std::vector<std::string> channels;
  /// Threads of OpenCV's DNN module; 0: OpenCV's default.
  int threads = 0;

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<SegmentationNetworkParams>& schema();
  /// Throws InputError naming the first value out of range or a channel list that does not match
  /// `classes`.
  void validate() const;
  /// The settings in a YAML file of config/segmenter.yaml's format, every other key at its default,
  /// validated; `model` must be set, to a path absolute or relative to the file's folder. Throws
  /// InputError naming the file (and the line and key where one is wrong).
  static SegmentationNetworkParams fromFile(const std::string& file);
  /// The output channel of the object, or -1 when it has none.
  int channelOf(const std::string& object) const;
};

}  // namespace stocs
