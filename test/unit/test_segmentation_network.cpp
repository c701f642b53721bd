// SegmentationNetwork on tiny ONNX models whose output is known from the input
// (test/data/segmentation/make_test_models.py): preprocessing, activations, resizing back, and
// every bad model or image named.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>

#include "stocs/segmentation/segmentation_network.h"
#include "stocs/util/error.h"
#include "test_support.h"

namespace stocs {
namespace {

using Params = SegmentationNetworkParams;

/// The pass-through model (output = input) read as probabilities, 3 classes, plain 0-1 input.
Params passThrough(const std::string& model = "test/data/segmentation/pass_through.onnx") {
  Params p;
  p.model = model;
  p.input_width = 16;
  p.input_height = 12;
  p.classes = 3;
  p.output = Params::Output::kProbabilities;
  return p;
}

/// A BGR image of one colour.
cv::Mat uniform(int width, int height, int b, int g, int r) {
  return cv::Mat(height, width, CV_8UC3, cv::Scalar(b, g, r));
}

/// Every pixel of each map equals the expected value.
void expectMaps(const std::vector<cv::Mat>& maps, const std::vector<double>& expected,
                cv::Size size) {
  ASSERT_EQ(maps.size(), expected.size());
  for (size_t c = 0; c < maps.size(); ++c) {
    ASSERT_EQ(maps[c].type(), CV_32FC1);
    ASSERT_EQ(maps[c].size(), size);
    double lo = 0, hi = 0;
    cv::minMaxLoc(maps[c], &lo, &hi);
    EXPECT_NEAR(lo, expected[c], 1e-5) << "channel " << c;
    EXPECT_NEAR(hi, expected[c], 1e-5) << "channel " << c;
  }
}

std::string errorOf(const Params& p) {
  try {
    SegmentationNetwork net(p);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SegmentationNetwork, ChannelOrderMeanAndScale) {
  const cv::Mat image = uniform(40, 30, 50, 100, 150);
  expectMaps(SegmentationNetwork(passThrough()).segment(image),
             {150 / 255.0, 100 / 255.0, 50 / 255.0}, image.size());
  Params bgr = passThrough();
  bgr.channel_order = Params::ChannelOrder::kBgr;
  bgr.mean_0 = 40;
  bgr.scale = 0.01f;
  expectMaps(SegmentationNetwork(bgr).segment(image), {0.1, 1.0, 1.0}, image.size());
}

TEST(SegmentationNetwork, SoftmaxAndSigmoidOfLogits) {
  Params p = passThrough();
  p.output = Params::Output::kLogits;
  p.scale = 0.01f;  // logits 1.5, 1.0, 0.5
  const cv::Mat image = uniform(16, 12, 50, 100, 150);
  const double e0 = std::exp(1.5), e1 = std::exp(1.0), e2 = std::exp(0.5);
  expectMaps(SegmentationNetwork(p).segment(image),
             {e0 / (e0 + e1 + e2), e1 / (e0 + e1 + e2), e2 / (e0 + e1 + e2)}, image.size());
  p.activation = Params::Activation::kSigmoid;
  expectMaps(SegmentationNetwork(p).segment(image),
             {1 / (1 + std::exp(-1.5)), 1 / (1 + std::exp(-1.0)), 1 / (1 + std::exp(-0.5))},
             image.size());
}

TEST(SegmentationNetwork, LetterboxPaddingStaysOutOfTheMaps) {
  // 64 x 24 into 16 x 12: the image fills rows 3 to 8, the rest is padding (zero input).
  Params p = passThrough();
  p.resize = Params::Resize::kLetterbox;
  const cv::Mat image = uniform(64, 24, 255, 255, 255);
  expectMaps(SegmentationNetwork(p).segment(image), {1, 1, 1}, image.size());
  // Stretched, the left and right halves of the image stay apart.
  cv::Mat halves = uniform(64, 24, 0, 0, 0);
  halves.colRange(32, 64).setTo(cv::Scalar(0, 0, 255));
  const std::vector<cv::Mat> maps = SegmentationNetwork(passThrough()).segment(halves);
  EXPECT_NEAR(maps[0].at<float>(12, 2), 0.0, 1e-5);
  EXPECT_NEAR(maps[0].at<float>(12, 61), 1.0, 1e-5);
}

TEST(SegmentationNetwork, SmallerOutputScaledToTheImage) {
  Params p = passThrough("test/data/segmentation/half_size.onnx");
  const cv::Mat image = uniform(640, 480, 0, 51, 255);
  expectMaps(SegmentationNetwork(p).segment(image), {1.0, 0.2, 0.0}, image.size());
}

TEST(SegmentationNetwork, UpsamplePicksChannelsInOrderAsFloatOrBytes) {
  const SegmentationNetwork net(passThrough());
  const cv::Mat image = uniform(64, 48, 0, 51, 255);  // channels 1.0, 0.2, 0.0
  const cv::Mat maps = net.outputMaps(image);
  EXPECT_EQ(maps.type(), CV_32FC3);
  EXPECT_EQ(maps.size(), cv::Size(16, 12));
  cv::Mat floats;
  SegmentationNetwork::upsample(maps, {2, 0}, image.size(), CV_32F, floats);
  ASSERT_EQ(floats.type(), CV_32FC2);
  ASSERT_EQ(floats.size(), image.size());
  EXPECT_NEAR(floats.at<cv::Vec2f>(20, 30)[0], 0.0, 1e-6);
  EXPECT_NEAR(floats.at<cv::Vec2f>(20, 30)[1], 1.0, 1e-6);
  // Into a buffer the caller owns (a message's data), as 8-bit round(255 p).
  std::vector<uint8_t> buffer(64 * 48 * 3);
  cv::Mat bytes(image.size(), CV_8UC3, buffer.data());
  SegmentationNetwork::upsample(maps, {1, 0, 2}, image.size(), CV_8U, bytes);
  ASSERT_EQ(bytes.data, buffer.data()) << "the caller's buffer was replaced";
  EXPECT_EQ(bytes.at<cv::Vec3b>(0, 0), cv::Vec3b(51, 255, 0));
  EXPECT_EQ(bytes.at<cv::Vec3b>(47, 63), cv::Vec3b(51, 255, 0));
}

TEST(SegmentationNetwork, ChannelOfObject) {
  Params p = passThrough();
  EXPECT_EQ(p.channelOf("2"), 2);
  EXPECT_EQ(p.channelOf("3"), -1);
  EXPECT_EQ(p.channelOf("cat"), -1);
  p.channels = {"-", "cat", "dog"};
  EXPECT_EQ(p.channelOf("dog"), 2);
  EXPECT_EQ(p.channelOf("-"), -1);
  EXPECT_EQ(p.channelOf("2"), -1);
}

TEST(SegmentationNetwork, BadModelsAndConfigurationsNamed) {
  EXPECT_NE(errorOf(passThrough("test/data/segmentation/none.onnx")).find("no such file"),
            std::string::npos);
  const auto corrupt = test::scratchDir("segmentation_network") / "corrupt.onnx";
  std::ofstream(corrupt) << "not a model";
  EXPECT_NE(errorOf(passThrough(corrupt.string())).find("not an ONNX model"), std::string::npos);
  Params seven = passThrough();
  seven.classes = 7;
  EXPECT_NE(errorOf(seven).find("output shape [1, 3, 12, 16] is not NCHW with 7 classes"),
            std::string::npos)
      << errorOf(seven);
  Params listed = passThrough();
  listed.channels = {"-", "cat"};
  EXPECT_NE(errorOf(listed).find("channels names 2 channels, but classes is 3"), std::string::npos);
  listed.channels = {"cat", "-", "cat"};
  EXPECT_NE(errorOf(listed).find("'cat' twice"), std::string::npos);
  Params wide = passThrough();
  wide.input_width = 0;
  EXPECT_NE(errorOf(wide).find("input_width"), std::string::npos);
}

/// A settings file with `text` in the scratch folder, beside a copy of the pass-through model.
std::string settingsFile(const std::string& text) {
  const auto dir = test::scratchDir("segmentation_settings");
  std::filesystem::copy_file("test/data/segmentation/pass_through.onnx", dir / "net.onnx",
                             std::filesystem::copy_options::overwrite_existing);
  std::ofstream(dir / "net.yaml") << text;
  return (dir / "net.yaml").string();
}

std::string settingsError(const std::string& text) {
  try {
    SegmentationNetworkParams::fromFile(settingsFile(text));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SegmentationNetwork, SettingsFileReadThroughTheSchema) {
  const std::string file = settingsFile(
      "model: net.onnx  # beside the file\ninput_width: 16\ninput_height: 12\n"
      "resize: letterbox\nchannel_order: bgr\nmean_0: 40\nscale: 0.01\noutput: probabilities\n"
      "classes: 3\nchannels: ['-', '2', '1']\nthreads: 1\n");
  const Params p = SegmentationNetworkParams::fromFile(file);
  EXPECT_EQ(p.model, (std::filesystem::path(file).parent_path() / "net.onnx").string());
  EXPECT_EQ(p.resize, Params::Resize::kLetterbox);
  EXPECT_EQ(p.channel_order, Params::ChannelOrder::kBgr);
  EXPECT_EQ(p.output, Params::Output::kProbabilities);
  EXPECT_EQ(p.activation, Params::Activation::kSoftmax);  // the default
  EXPECT_FLOAT_EQ(p.mean_0, 40);
  EXPECT_EQ(p.channelOf("1"), 2);
  expectMaps(SegmentationNetwork(p).segment(uniform(16, 12, 50, 100, 150)), {0.1, 1.0, 1.0},
             cv::Size(16, 12));
}

TEST(SegmentationNetwork, SettingsFileMistakesNamed) {
  const std::string good = "model: net.onnx\nclasses: 3\n";
  for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
           {good + "input_widht: 16\n", "net.yaml:3: input_widht: unknown key"},
           {good + "input_width: 0\n", "net.yaml:3: input_width: 0 px is outside [8, 8192]"},
           {good + "input_width: wide\n",
            "net.yaml:3: input_width: expected an integer, got 'wide'"},
           {good + "scale: 1e39\n", "net.yaml:3: scale: expected a number, got '1e39'"},
           {good + "resize: crop\n", "net.yaml:3: resize: 'crop' is not one of stretch, letterbox"},
           {good + "channels: cat\n", "net.yaml:3: channels: expected a list"},
           {good + "channels: ['-', '1']\n",
            "net.yaml: channels names 2 channels, but classes is 3"},
           {"classes: 3\n", "net.yaml: model is not set"},
           {"model: package://stocs_ros/models/segmenter.onnx\n",
            "model 'package://stocs_ros/models/segmenter.onnx' is a URL"},
           {"[1, 2]\n", "net.yaml: expected a map of keys"},
           {good + "[a, b]: 1\n", "net.yaml:3: ?: expected a key, not a list or map"},
           {"model: [\n", "net.yaml: invalid YAML"}}) {
    EXPECT_NE(settingsError(text).find(message), std::string::npos)
        << text << " gave: " << settingsError(text);
  }
  EXPECT_NE(
      errorOf(SegmentationNetworkParams::fromFile(settingsFile("model: net.onnx\nclasses: 7\n")))
          .find("is not NCHW with 7 classes"),
      std::string::npos);
}

TEST(SegmentationNetwork, BadImagesNamed) {
  const SegmentationNetwork net(passThrough());
  EXPECT_THROW(net.segment(cv::Mat()), InputError);
  EXPECT_THROW(net.segment(cv::Mat(12, 16, CV_8UC1, cv::Scalar(0))), InputError);
  EXPECT_THROW(net.segment(cv::Mat(12, 16, CV_32FC3, cv::Scalar::all(0))), InputError);
}

}  // namespace
}  // namespace stocs
