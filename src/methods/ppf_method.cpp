// "ppf": OpenCV's point pair feature Hough voting (cv::ppf_match_3d::PPF3DDetector, Drost et al.
// 2010) on the hard segment. Parameters, from the surface_matching documentation
// (opencv2/surface_matching.hpp, "Parameter Tuning", and ppf_match_3d.hpp) and Drost et al.:
//  * relativeSamplingStep 0.05: "values in the range of 0.025 - 0.05 seem adequate"; 0.05 is
//    Drost's tau_d and the resolution of the model samples given (4% of the diameter), so no
//    detail is lost, and memory (quadratic in the sampled points) stays small.
//  * relativeDistanceStep 0.05: "expected to equate to" relativeSamplingStep. (OpenCV 4.6 in fact
//    quantises distances with relativeSamplingStep and ignores this value.)
//  * numAngles 30: the default and Drost's n_angle; 20-25 only "for very noisy scenes".
//  * match(relativeSceneSampleStep 1/5, relativeSceneDistance 0.05): the scene is "again sampled
//    by RelativeSamplingStep" and 1/5 of it serves as reference points (the default, and Drost's
//    choice); the class documentation's example uses exactly (0.05, 0.05) and (1/5, 0.05).
//  * Pose clustering (setSearchParams): OpenCV's defaults are the position threshold
//    relativeSamplingStep in model units (5 cm for a model in metres) and a rotation threshold of
//    (360 / angle step in radians) degrees, i.e. none; what they stand for is set instead:
//    relativeSamplingStep x the model's bounding-box diagonal (the "diameter" every relative value
//    refers to) and one angle step, 360 / numAngles degrees. Unweighted averaging (the default).
// No time or base budget exists: one match() votes with every reference point, and the library is
// deterministic and single-threaded (Debian's build has no OpenMP). The detector is trained once
// per model (prepare(), or the first estimate() on it) and kept. The final pose goes through the
// refinement every baseline shares (baseline_method.h) rather than cv::ppf_match_3d::ICP, which
// the OpenCV sample applies: one refinement for all methods keeps the comparison on the search.
// Score: the votes of the best pose cluster.
#include <opencv2/surface_matching.hpp>

#include <cmath>
#include <map>
#include <string_view>

#include "baseline_method.h"
#include "baseline_methods.h"

namespace stocs {
namespace {

constexpr double kRelativeSamplingStep = 0.05;
constexpr double kRelativeDistanceStep = 0.05;
constexpr double kNumAngles = 30;
constexpr double kRelativeSceneSampleStep = 1.0 / 5.0;
constexpr double kRelativeSceneDistance = 0.05;

/// N x 6 (x, y, z, nx, ny, nz), CV_32F: OpenCV's point cloud with normals.
cv::Mat pointsWithNormals(const std::vector<Eigen::Vector3f>& points,
                          const std::vector<Eigen::Vector3f>& normals) {
  cv::Mat m(static_cast<int>(points.size()), 6, CV_32F);
  for (int i = 0; i < m.rows; ++i) {
    float* row = m.ptr<float>(i);
    for (int k = 0; k < 3; ++k) {
      row[k] = points[i][k];
      row[3 + k] = normals[i][k];
    }
  }
  return m;
}

Eigen::AlignedBox3f boundingBox(const std::vector<Eigen::Vector3f>& points) {
  Eigen::AlignedBox3f box;
  for (const Eigen::Vector3f& p : points) box.extend(p);
  return box;
}

/// OpenCV quantises each axis by its extent (samplePCByQuantization) and indexes out of bounds
/// when an extent is 0, so such point sets (a plane seen exactly face-on) are not given to it.
bool hasVolume(const Eigen::AlignedBox3f& box) {
  return (box.sizes().array() > 0).all();
}

/// Identifies a model by its samples, so that a trained detector is reused only for that model.
size_t fingerprint(const ObjectModel& model) {
  const auto bytes = [](const std::vector<Eigen::Vector3f>& v) {
    return std::hash<std::string_view>{}(std::string_view(reinterpret_cast<const char*>(v.data()),
                                                          v.size() * sizeof(Eigen::Vector3f)));
  };
  return bytes(model.points) ^ (bytes(model.normals) * 0x9E3779B97F4A7C15ull);
}

class PpfMethod : public BaselineMethod {
 public:
  using BaselineMethod::BaselineMethod;
  std::string name() const override { return "ppf"; }
  void prepare(const PreparedModel& model) override { detector(model.model); }

 protected:
  std::optional<BaselineHypothesis> search(const SoftSegment& segment,
                                           const ObjectInput& input) override {
    cv::ppf_match_3d::PPF3DDetector* d = detector(input.model->model);
    if (!d || !hasVolume(boundingBox(segment.points))) return std::nullopt;
    std::vector<cv::ppf_match_3d::Pose3DPtr> poses;  // best first
    d->match(pointsWithNormals(segment.points, segment.normals), poses, kRelativeSceneSampleStep,
             kRelativeSceneDistance);
    if (poses.empty()) return std::nullopt;
    BaselineHypothesis h;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) h.pose.matrix()(r, c) = static_cast<float>(poses[0]->pose(r, c));
    }
    h.score = static_cast<double>(poses[0]->numVotes);
    h.hypotheses = static_cast<long>(poses.size());
    return h;
  }

 private:
  /// The detector trained on `model`, trained on first use; null for a model OpenCV cannot sample.
  cv::ppf_match_3d::PPF3DDetector* detector(const ObjectModel& model) {
    auto [it, inserted] = detectors_.try_emplace(fingerprint(model));
    if (!inserted) return it->second.get();
    const Eigen::AlignedBox3f box = boundingBox(model.points);
    if (!hasVolume(box)) return nullptr;
    auto d = std::make_unique<cv::ppf_match_3d::PPF3DDetector>(kRelativeSamplingStep,
                                                               kRelativeDistanceStep, kNumAngles);
    d->setSearchParams(kRelativeSamplingStep * box.diagonal().norm(), 2 * M_PI / kNumAngles);
    d->trainModel(pointsWithNormals(model.points, model.normals));
    it->second = std::move(d);
    return it->second.get();
  }

  std::map<size_t, std::unique_ptr<cv::ppf_match_3d::PPF3DDetector>> detectors_;
};

}  // namespace

std::unique_ptr<PoseMethod> makePpfMethod(const MethodOptions& options) {
  return std::make_unique<PpfMethod>(options.hard_threshold);
}

}  // namespace stocs
