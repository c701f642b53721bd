#include "stocs/segmentation/segmentation_network.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>

#include "stocs/util/error.h"

namespace stocs {
namespace {

using Params = SegmentationNetworkParams;

cv::dnn::Net loadNet(const std::string& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw InputError(fmt::format("segmentation model {}: no such file", file));
  }
  try {
    cv::dnn::Net net = cv::dnn::readNetFromONNX(file);
    if (net.empty()) throw InputError(fmt::format("segmentation model {}: empty network", file));
    net.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
    net.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
    return net;
  } catch (const cv::Exception& e) {
    throw InputError(
        fmt::format("segmentation model {}: not an ONNX model OpenCV reads ({})", file, e.err));
  }
}

/// The part of the input that holds the image (all of it, or the letterbox's inside).
cv::Rect imageArea(const Params& p, cv::Size image) {
  if (p.resize == Params::Resize::kStretch) return {0, 0, p.input_width, p.input_height};
  const double s = std::min(static_cast<double>(p.input_width) / image.width,
                            static_cast<double>(p.input_height) / image.height);
  const int w = std::max(1, static_cast<int>(std::lround(image.width * s)));
  const int h = std::max(1, static_cast<int>(std::lround(image.height * s)));
  return {(p.input_width - w) / 2, (p.input_height - h) / 2, w, h};
}

cv::Mat inputBlob(const Params& p, const cv::Mat& bgr) {
  cv::Mat input(p.input_height, p.input_width, CV_8UC3, cv::Scalar::all(0));
  cv::resize(bgr, input(imageArea(p, bgr.size())), imageArea(p, bgr.size()).size(), 0, 0,
             cv::INTER_AREA);
  return cv::dnn::blobFromImage(input, p.scale, cv::Size(),
                                cv::Scalar(p.mean_0, p.mean_1, p.mean_2),
                                p.channel_order == Params::ChannelOrder::kRgb, false, CV_32F);
}

/// The output blob's channels as H x W images (views into the blob).
std::vector<cv::Mat> outputChannels(const cv::Mat& blob) {
  std::vector<cv::Mat> planes;
  for (int c = 0; c < blob.size[1]; ++c) {
    planes.emplace_back(blob.size[2], blob.size[3], CV_32F,
                        const_cast<float*>(blob.ptr<float>(0, c)));
  }
  return planes;
}

void softmax(std::vector<cv::Mat>& planes) {
  cv::Mat top = planes[0].clone();
  for (const cv::Mat& m : planes) cv::max(top, m, top);
  cv::Mat sum = cv::Mat::zeros(top.size(), CV_32F);
  for (cv::Mat& m : planes) {
    cv::exp(m - top, m);
    sum += m;
  }
  for (cv::Mat& m : planes) m /= sum;
}

void sigmoid(std::vector<cv::Mat>& planes) {
  for (cv::Mat& m : planes) {
    cv::exp(-m, m);
    m = 1.0f / (1.0f + m);
  }
}

}  // namespace

struct SegmentationNetwork::Impl {
  Params params;
  mutable cv::dnn::Net net;

  cv::Mat forward(const cv::Mat& bgr) const {
    net.setInput(inputBlob(params, bgr));
    try {
      return net.forward();
    } catch (const cv::Exception& e) {
      throw InputError(fmt::format("segmentation model {}: cannot run ({})", params.model, e.err));
    }
  }

  /// Throws InputError unless the output is NCHW with the configured classes.
  void checkOutput(const cv::Mat& blob) const {
    if (blob.dims != 4 || blob.size[0] != 1 || blob.size[1] != params.classes) {
      std::vector<int> shape(blob.size.p, blob.size.p + blob.dims);
      throw InputError(fmt::format(
          "segmentation model {}: output shape [{}] is not NCHW with {} classes (classes)",
          params.model, fmt::join(shape, ", "), params.classes));
    }
  }
};

SegmentationNetwork::SegmentationNetwork(const SegmentationNetworkParams& params)
    : impl_(std::make_unique<Impl>()) {
  params.validate();
  impl_->params = params;
  if (params.threads > 0) cv::setNumThreads(params.threads);
  impl_->net = loadNet(params.model);
  impl_->checkOutput(impl_->forward(
      cv::Mat(params.input_height, params.input_width, CV_8UC3, cv::Scalar::all(0))));
}

SegmentationNetwork::~SegmentationNetwork() = default;
SegmentationNetwork::SegmentationNetwork(SegmentationNetwork&&) noexcept = default;
SegmentationNetwork& SegmentationNetwork::operator=(SegmentationNetwork&&) noexcept = default;

const SegmentationNetworkParams& SegmentationNetwork::params() const {
  return impl_->params;
}

std::vector<cv::Mat> SegmentationNetwork::segment(const cv::Mat& bgr) const {
  const cv::Mat maps = outputMaps(bgr);
  std::vector<cv::Mat> planes(maps.channels());
  for (int c = 0; c < maps.channels(); ++c) upsample(maps, {c}, bgr.size(), CV_32F, planes[c]);
  return planes;
}

cv::Mat SegmentationNetwork::outputMaps(const cv::Mat& bgr) const {
  if (bgr.empty() || bgr.type() != CV_8UC3) {
    throw InputError(
        fmt::format("segmentation input: expected a non-empty 8-bit 3-channel image, "
                    "got {}x{} with {} channels of depth {}",
                    bgr.cols, bgr.rows, bgr.channels(), bgr.depth()));
  }
  const Params& p = impl_->params;
  const cv::Mat blob = impl_->forward(bgr);
  impl_->checkOutput(blob);
  // The image's part of the output, which may be smaller than the input.
  const cv::Rect area = imageArea(p, bgr.size());
  const double sx = static_cast<double>(blob.size[3]) / p.input_width;
  const double sy = static_cast<double>(blob.size[2]) / p.input_height;
  const cv::Rect out_area =
      cv::Rect(cvRound(area.x * sx), cvRound(area.y * sy), std::max(1, cvRound(area.width * sx)),
               std::max(1, cvRound(area.height * sy))) &
      cv::Rect(0, 0, blob.size[3], blob.size[2]);
  std::vector<cv::Mat> planes = outputChannels(blob);
  for (cv::Mat& m : planes) m = m(out_area).clone();
  if (p.output == Params::Output::kLogits) {
    p.activation == Params::Activation::kSoftmax ? softmax(planes) : sigmoid(planes);
  }
  for (cv::Mat& m : planes) {
    if (cv::checkRange(m, true) == false) {
      throw InputError(fmt::format("segmentation model {}: output holds NaN or infinity", p.model));
    }
    // Clamped here, at the output's size: bilinear upsampling keeps values in [0, 1].
    cv::min(m, 1.0, m);
    cv::max(m, 0.0, m);
  }
  cv::Mat maps;
  cv::merge(planes, maps);
  return maps;
}

void SegmentationNetwork::upsample(const cv::Mat& maps, const std::vector<int>& channels,
                                   cv::Size size, int depth, cv::Mat& out) {
  // The channels picked at the output's size, so the full-size image is written once (twice for
  // bytes: upsampled as floats, then rounded into `out`).
  CV_Assert(depth == CV_8U || depth == CV_32F);
  cv::Mat picked(maps.size(), CV_32FC(static_cast<int>(channels.size())));
  std::vector<int> from_to;
  for (size_t i = 0; i < channels.size(); ++i) {
    from_to.push_back(channels[i]);
    from_to.push_back(static_cast<int>(i));
  }
  cv::mixChannels(&maps, 1, &picked, 1, from_to.data(), channels.size());
  if (depth == CV_8U) {
    cv::Mat floats;
    cv::resize(picked, floats, size, 0, 0, cv::INTER_LINEAR);
    floats.convertTo(out, CV_8U, 255.0);
    return;
  }
  cv::resize(picked, out, size, 0, 0, cv::INTER_LINEAR);
  // Bilinear weights are not negative, but their float sum can exceed 1 by a rounding step.
  cv::Mat values = out.reshape(1);
  cv::min(values, 1.0, values);
}

}  // namespace stocs
