#include "network_probability_source.h"

#include <fmt/format.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <optional>

#include "stocs/segmentation/segmentation_network.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

class NetworkProbabilitySource : public ProbabilitySource {
 public:
  NetworkProbabilitySource(std::string spec, SegmentationNetwork network, const BopDataset& dataset)
      : spec_(std::move(spec)), network_(std::move(network)), dataset_(dataset) {}

  std::string spec() const override { return spec_; }

  bool available(int scene_id, int im_id, int obj_id) const override {
    std::error_code ec;
    return channelOfObject(obj_id) >= 0 &&
           std::filesystem::exists(dataset_.rgbPath(scene_id, im_id), ec);
  }

  cv::Mat load(int scene_id, int im_id, int obj_id) const override {
    const int channel = channelOfObject(obj_id);
    if (channel < 0) {
      throw InputError(fmt::format("{}: object {} has no output channel", spec_, obj_id));
    }
    return maps(scene_id, im_id)[channel];
  }

 private:
  /// The channel named by `obj_id` ("5") or its BOP model file's stem ("obj_000005"); -1: none.
  int channelOfObject(int obj_id) const {
    const int by_id = network_.params().channelOf(std::to_string(obj_id));
    return by_id >= 0 ? by_id : network_.params().channelOf(fmt::format("obj_{:06d}", obj_id));
  }

  /// The frame's maps, kept for the objects that follow (one frame at a time).
  const std::vector<cv::Mat>& maps(int scene_id, int im_id) const {
    const auto key = std::make_pair(scene_id, im_id);
    if (!cached_ || cached_->first != key) {
      const std::string file = dataset_.rgbPath(scene_id, im_id).string();
      const cv::Mat bgr = cv::imread(file, cv::IMREAD_COLOR);
      if (bgr.empty()) throw InputError(fmt::format("{}: cannot read the colour image", file));
      cached_.emplace(key, network_.segment(bgr));
    }
    return cached_->second;
  }

  std::string spec_;
  SegmentationNetwork network_;
  const BopDataset& dataset_;
  mutable std::optional<std::pair<std::pair<int, int>, std::vector<cv::Mat>>> cached_;
};

bool isNumber(const std::string& text) {
  return !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
}

/// A BOP dataset names its objects by obj_id: a channel list must name obj_ids ("5"), model file
/// stems ("obj_000005") or '-'.
void requireObjectIds(const std::string& file, const std::vector<std::string>& channels) {
  const std::string stem = "obj_";
  for (const std::string& name : channels) {
    const bool model_stem =
        name.compare(0, stem.size(), stem) == 0 && isNumber(name.substr(stem.size()));
    if (name != "-" && !isNumber(name) && !model_stem) {
      throw InputError(
          fmt::format("{}: channels names '{}'; for a BOP dataset name each channel's obj_id or "
                      "model file stem (\"5\" or \"obj_000005\"; \"-\" for none)",
                      file, name));
    }
  }
}

}  // namespace

std::unique_ptr<ProbabilitySource> makeNetworkProbabilitySource(const std::string& spec,
                                                                const std::string& file,
                                                                const BopDataset& dataset) {
  const std::string extension = std::filesystem::path(file).extension().string();
  SegmentationNetworkParams params;
  if (extension == ".yaml" || extension == ".yml") {
    params = SegmentationNetworkParams::fromFile(file);
    requireObjectIds(file, params.channels);
  } else {
    params.model = file;
  }
  return std::make_unique<NetworkProbabilitySource>(spec, SegmentationNetwork(params), dataset);
}

}  // namespace stocs
