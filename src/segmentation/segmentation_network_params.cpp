#include "stocs/segmentation/segmentation_network_params.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "stocs/util/error.h"
#include "stocs/util/param_file.h"

namespace stocs {

const ParamSet<SegmentationNetworkParams>& SegmentationNetworkParams::schema() {
  using P = SegmentationNetworkParams;
  static const ParamSet<P> schema =
      ParamSet<P>()
          .add(&P::model, "model", "", std::nullopt, "the ONNX file of the network")
          .add(&P::input_width, "input_width", "px", ParamRange::closed(8, 8192),
               "width of the network's input; images are resized to it")
          .add(&P::input_height, "input_height", "px", ParamRange::closed(8, 8192),
               "height of the network's input")
          .choice(&P::resize, "resize",
                  {{"stretch", P::Resize::kStretch}, {"letterbox", P::Resize::kLetterbox}},
                  "stretch to the input size, or keep the aspect and pad with zero (letterbox)")
          .choice(&P::channel_order, "channel_order",
                  {{"rgb", P::ChannelOrder::kRgb}, {"bgr", P::ChannelOrder::kBgr}},
                  "the colour channel order the network takes")
          .add(&P::mean_0, "mean_0", "", ParamRange::closed(-1000, 1000),
               "subtracted from the input's first channel (0-255 units), before the scale")
          .add(&P::mean_1, "mean_1", "", ParamRange::closed(-1000, 1000),
               "subtracted from the input's second channel")
          .add(&P::mean_2, "mean_2", "", ParamRange::closed(-1000, 1000),
               "subtracted from the input's third channel")
          .add(&P::scale, "scale", "", ParamRange::aboveUpTo(0, 1000),
               "input = (pixel - mean) * scale")
          .choice(&P::output, "output",
                  {{"logits", P::Output::kLogits}, {"probabilities", P::Output::kProbabilities}},
                  "what the NCHW output holds; logits go through the activation")
          .choice(&P::activation, "activation",
                  {{"softmax", P::Activation::kSoftmax}, {"sigmoid", P::Activation::kSigmoid}},
                  "logits to probabilities: softmax over the channels or a sigmoid per channel")
          .add(&P::classes, "classes", "", ParamRange::closed(1, 1000),
               "output channels the model must have")
          .add(&P::channels, "channels", "", std::nullopt,
               "the object of each output channel in order, '-' for none; empty: channel k is "
               "obj_id k")
          .add(&P::threads, "threads", "", ParamRange::closed(0, 256),
               "threads of OpenCV's DNN module (process-wide); 0: OpenCV's default");
  return schema;
}

void SegmentationNetworkParams::validate() const {
  schema().validate(*this);
  if (!channels.empty() && static_cast<int>(channels.size()) != classes) {
    throw InputError(
        fmt::format("channels names {} channels, but classes is {}", channels.size(), classes));
  }
  for (size_t i = 0; i < channels.size(); ++i) {
    if (channels[i] != "-" &&
        std::find(channels.begin(), channels.begin() + i, channels[i]) != channels.begin() + i) {
      throw InputError(fmt::format("channels names '{}' twice", channels[i]));
    }
  }
}

SegmentationNetworkParams SegmentationNetworkParams::fromFile(const std::string& file) {
  SegmentationNetworkParams p;
  readParamFile(file, schema(), p);
  if (p.model.empty()) throw InputError(fmt::format("{}: model is not set", file));
  if (p.model.find("://") != std::string::npos) {
    throw InputError(fmt::format(
        "{}: model '{}' is a URL; give the ONNX file's path, absolute or relative to this file",
        file, p.model));
  }
  p.model = (std::filesystem::path(file).parent_path() / p.model).lexically_normal().string();
  try {
    p.validate();
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", file, e.what()));
  }
  return p;
}

int SegmentationNetworkParams::channelOf(const std::string& object) const {
  if (channels.empty()) {
    try {
      size_t end = 0;
      const int k = std::stoi(object, &end);
      return end == object.size() && k >= 0 && k < classes ? k : -1;
    } catch (const std::exception&) {
      return -1;
    }
  }
  const auto it = std::find(channels.begin(), channels.end(), object);
  return object == "-" || it == channels.end() ? -1 : static_cast<int>(it - channels.begin());
}

}  // namespace stocs
