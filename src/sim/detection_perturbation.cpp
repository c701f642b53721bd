#include "stocs/sim/detection_perturbation.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "stocs/util/random.h"

namespace stocs {
namespace {

constexpr int kMinMaskPixels = 20;

float uniform(Rng& rng, float lo, float hi) {
  return lo + (hi - lo) * uniform01(rng);
}

}  // namespace

std::vector<InstanceMask> perturbedMasks(const SegmentationScene& scene, int obj_id,
                                         const SegmentationNoiseParams& params, uint64_t seed) {
  const cv::Mat map = simulateSegmentation(scene, obj_id, params, seed);
  cv::Mat parts;
  const int count = cv::connectedComponents(map > 0.5f, parts, 8, CV_32S);
  Rng rng(streamSeed(seed, 0x5C0BE));
  std::vector<InstanceMask> masks;
  for (int k = 1; k < count; ++k) {
    InstanceMask m;
    m.mask = parts == k;
    if (cv::countNonZero(m.mask) < kMinMaskPixels) continue;
    m.class_id = obj_id;
    const float mean = static_cast<float>(cv::mean(map, m.mask)[0]);
    m.score = std::clamp(mean + uniform(rng, -0.15f, 0.15f), 0.05f, 1.0f);
    masks.push_back(std::move(m));
  }
  return masks;
}

BoxDetection perturbedBox(const BoxDetection& box, uint64_t seed) {
  Rng rng(seed);
  const float w = box.box.width, h = box.box.height;
  const float dx = uniform(rng, -0.15f, 0.15f) * w, dy = uniform(rng, -0.15f, 0.15f) * h;
  const float left = uniform(rng, 0, 0.2f) * w, right = uniform(rng, 0, 0.2f) * w;
  const float top = uniform(rng, 0, 0.2f) * h, bottom = uniform(rng, 0, 0.2f) * h;
  BoxDetection out = box;
  out.box =
      cv::Rect2f(box.box.x + dx - left, box.box.y + dy - top, w + left + right, h + top + bottom);
  out.score = uniform(rng, 0.5f, 1.0f);
  return out;
}

}  // namespace stocs
