#include "stocs/probability_source.h"

#include <fmt/format.h>

#include <filesystem>
#include <opencv2/core.hpp>

#include "stocs/error.h"

namespace stocs {
namespace {

/// The network maps shipped with the dataset (`prob/{im}_{obj}.png`).
class RealProbabilitySource : public ProbabilitySource {
 public:
  explicit RealProbabilitySource(const BopDataset& dataset) : dataset_(dataset) {}
  std::string spec() const override { return "real"; }
  bool available(int scene_id, int im_id, int obj_id) const override {
    std::error_code ec;
    return std::filesystem::exists(dataset_.probabilityPath(scene_id, im_id, obj_id), ec);
  }
  cv::Mat load(int scene_id, int im_id, int obj_id) const override {
    return dataset_.loadProbability(scene_id, im_id, obj_id);
  }

 private:
  const BopDataset& dataset_;
};

}  // namespace

std::unique_ptr<ProbabilitySource> makeProbabilitySource(const std::string& spec,
                                                         const BopDataset& dataset,
                                                         uint64_t /*seed*/) {
  if (spec == "real") return std::make_unique<RealProbabilitySource>(dataset);
  throw InputError(fmt::format("unknown probability source '{}'; known: real", spec));
}

}  // namespace stocs
