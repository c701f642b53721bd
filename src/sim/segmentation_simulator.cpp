#include "stocs/sim/segmentation_simulator.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <set>

#include "stocs/util/error.h"
#include "stocs/util/random.h"

namespace stocs {
namespace {

/// The presets, clean to very noisy. "mild" is tuned to the paper's recall on synthetic test
/// images (95.3%), "noisy" to its recall on real images (77.9%); docs/simulator.md has what each
/// gives on ../shared/datasets (`stocs simstats`).
const std::vector<std::pair<std::string, SegmentationNoiseParams>>& presets() {
  static const std::vector<std::pair<std::string, SegmentationNoiseParams>> table = [] {
    SegmentationNoiseParams clean;
    clean.confidence = 0.95f;
    clean.bleed_px = 1.0f;
    clean.noise = 0.02f;
    clean.confusion_level = 0.45f;
    clean.absent_blobs = 2;
    clean.absent_blob_level = 0.35f;

    SegmentationNoiseParams mild = clean;
    mild.confidence = 0.9f;
    mild.missed_fraction = 0.06f;
    mild.bleed_px = 2.0f;
    mild.neighbour_fraction = 0.05f;
    mild.lookalike_fraction = 0.01f;
    mild.noise = 0.05f;
    mild.confusion_level = 0.55f;
    mild.absent_blobs = 3;
    mild.absent_blob_level = 0.4f;

    SegmentationNoiseParams noisy = mild;
    noisy.confidence = 0.8f;
    noisy.missed_fraction = 0.25f;
    noisy.bleed_px = 3.0f;
    noisy.neighbour_fraction = 0.12f;
    noisy.lookalike_fraction = 0.03f;
    noisy.noise = 0.08f;
    noisy.confusion_level = 0.6f;
    noisy.absent_blobs = 4;
    noisy.absent_blob_level = 0.45f;

    SegmentationNoiseParams very_noisy = noisy;
    very_noisy.confidence = 0.7f;
    very_noisy.missed_fraction = 0.4f;
    very_noisy.bleed_px = 5.0f;
    very_noisy.neighbour_fraction = 0.25f;
    very_noisy.lookalike_fraction = 0.06f;
    very_noisy.noise = 0.12f;
    very_noisy.confusion_level = 0.65f;
    very_noisy.absent_blobs = 5;
    very_noisy.absent_blob_level = 0.5f;
    return std::vector<std::pair<std::string, SegmentationNoiseParams>>{
        {"clean", clean}, {"mild", mild}, {"noisy", noisy}, {"very-noisy", very_noisy}};
  }();
  return table;
}

/// Gaussian noise smoothed over about `scale_px` pixels (bicubic upsampling of a coarse grid),
/// standardised to mean 0 and standard deviation 1.
cv::Mat smoothField(cv::Size size, float scale_px, cv::RNG& rng) {
  const int cols = std::max(2, static_cast<int>(std::ceil(size.width / scale_px)) + 1);
  const int rows = std::max(2, static_cast<int>(std::ceil(size.height / scale_px)) + 1);
  cv::Mat grid(rows, cols, CV_32F);
  rng.fill(grid, cv::RNG::NORMAL, 0, 1);
  cv::Mat field;
  cv::resize(grid, field, size, 0, 0, cv::INTER_CUBIC);
  cv::Scalar mean, stddev;
  cv::meanStdDev(field, mean, stddev);
  field = (field - mean[0]) / std::max(stddev[0], 1e-6);
  return field;
}

/// The value of `field` that a share `fraction` of the pixels of `mask` exceed.
float upperQuantile(const cv::Mat& field, const cv::Mat& mask, float fraction) {
  std::vector<float> values;
  for (int v = 0; v < field.rows; ++v) {
    const float* f = field.ptr<float>(v);
    const uint8_t* m = mask.ptr<uint8_t>(v);
    for (int u = 0; u < field.cols; ++u) {
      if (m[u]) values.push_back(f[u]);
    }
  }
  if (values.empty() || fraction <= 0) return std::numeric_limits<float>::infinity();
  const size_t k = std::min(values.size() - 1,
                            static_cast<size_t>((1.0f - std::min(fraction, 1.0f)) * values.size()));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k];
}

/// 0 below `threshold`, 1 a quarter standard deviation above it, linear in between: soft-edged
/// regions of a smooth field.
cv::Mat softAbove(const cv::Mat& field, float threshold) {
  if (!std::isfinite(threshold)) return cv::Mat::zeros(field.size(), CV_32F);
  cv::Mat gate = (field - threshold) * 4.0f;
  return cv::min(cv::max(gate, 0.0f), 1.0f);
}

/// Throws InputError for a label image that is not a non-empty CV_32SC1 image, or an RGB image of
/// another type or size.
void checkScene(const SegmentationScene& scene) {
  const cv::Mat& labels = scene.labels;
  if (labels.empty() || labels.type() != CV_32SC1) {
    throw InputError("segmentation simulator: the label image must be a non-empty CV_32SC1 image");
  }
  if (!scene.rgb.empty() && (scene.rgb.type() != CV_8UC3 || scene.rgb.size() != labels.size())) {
    throw InputError(fmt::format(
        "segmentation simulator: the RGB image must be CV_8UC3 of {}x{} like the labels; it is "
        "{}x{} with {} channels",
        labels.cols, labels.rows, scene.rgb.cols, scene.rgb.rows, scene.rgb.channels()));
  }
}

/// The pixels of the target object and those of the other objects (255, else 0).
struct SceneMasks {
  cv::Mat target, other;
};

/// The masks of a scene; throws InputError for a label without an object id.
SceneMasks sceneMasks(const SegmentationScene& scene, int target_obj_id) {
  const cv::Mat& labels = scene.labels;
  const cv::Size size = labels.size();
  SceneMasks masks{cv::Mat(size, CV_8UC1, cv::Scalar(0)), cv::Mat(size, CV_8UC1, cv::Scalar(0))};
  for (int v = 0; v < size.height; ++v) {
    for (int u = 0; u < size.width; ++u) {
      const int l = labels.at<int>(v, u);
      if (l == 0) continue;
      if (l < 0 || l > static_cast<int>(scene.obj_ids.size())) {
        throw InputError(fmt::format(
            "segmentation simulator: label {} at pixel (u={}, v={}) has no object id ({} given)", l,
            u, v, scene.obj_ids.size()));
      }
      (scene.obj_ids[l - 1] == target_obj_id ? masks.target : masks.other).at<uint8_t>(v, u) = 255;
    }
  }
  return masks;
}

/// The random draws of one seed: shares and smooth fields.
struct RandomLayout {
  float missed_share, neighbour_share;
  cv::Mat bleed_field, missed_field, neighbour_field, lookalike_field, noise_field;
};

/// The layout of `seed`. Every random field is drawn whatever the parameters, so that all presets
/// share one random layout for a seed and a noisier preset only grows the same missed and
/// false-positive regions.
RandomLayout drawLayout(cv::Size size, const SegmentationNoiseParams& params, uint64_t seed) {
  cv::RNG rng(seed);
  RandomLayout layout;
  // One statement per draw: the order of the draws is the layout.
  layout.missed_share = params.missed_fraction * rng.uniform(0.5f, 1.5f);
  layout.neighbour_share = params.neighbour_fraction * rng.uniform(0.5f, 1.5f);
  layout.bleed_field = smoothField(size, 2 * params.blob_px, rng);
  layout.missed_field = smoothField(size, params.blob_px, rng);
  layout.neighbour_field = smoothField(size, params.blob_px, rng);
  layout.lookalike_field = smoothField(size, 1.5f * params.blob_px, rng);
  layout.noise_field = smoothField(size, 3, rng);
  return layout;
}

/// `a` and `b` (fields of mean 0 and variance 1) blended by `weight`, at variance 1 again.
cv::Mat blendFields(const cv::Mat& a, const cv::Mat& b, float weight) {
  const float norm = std::sqrt((1 - weight) * (1 - weight) + weight * weight);
  return (a * (1 - weight) + b * weight) / norm;
}

/// The layout of `seeds.from` blended into that of `seeds.to`; that of `seeds.from` alone, drawn
/// once, at weight 0.
RandomLayout drawLayout(cv::Size size, const SegmentationNoiseParams& params,
                        const SegmentationSeeds& seeds) {
  RandomLayout layout = drawLayout(size, params, seeds.from);
  if (seeds.weight <= 0) return layout;
  const RandomLayout to = drawLayout(size, params, seeds.to);
  const float w = std::min(seeds.weight, 1.0f);
  layout.missed_share += w * (to.missed_share - layout.missed_share);
  layout.neighbour_share += w * (to.neighbour_share - layout.neighbour_share);
  for (auto field :
       {&RandomLayout::bleed_field, &RandomLayout::missed_field, &RandomLayout::neighbour_field,
        &RandomLayout::lookalike_field, &RandomLayout::noise_field}) {
    layout.*field = blendFields(layout.*field, to.*field, w);
  }
  return layout;
}

/// The object as found, bleeding over its outline by an amount that varies along it, at the
/// preset's confidence, with its missed regions.
cv::Mat foundObject(const cv::Mat& target, const RandomLayout& layout,
                    const SegmentationNoiseParams& params) {
  cv::Mat found;
  target.convertTo(found, CV_32F, 1.0 / 255);
  if (params.bleed_px > 0) {
    cv::Mat spread;
    cv::GaussianBlur(found, spread, cv::Size(0, 0), params.bleed_px);
    const cv::Mat reach = cv::min(cv::max(0.75f + 0.35f * layout.bleed_field, 0.2f), 1.0f);
    found = cv::max(found, cv::min(2.0f * spread, 1.0f).mul(reach));
  }
  found *= params.confidence;
  // Missed regions, which also stop the bleeding next to them.
  const cv::Mat missed = softAbove(layout.missed_field,
                                   upperQuantile(layout.missed_field, target, layout.missed_share));
  return found.mul(1.0f - missed) + cv::min(found, params.missed_level).mul(missed);
}

/// The other objects' pixels of the instances that come within 2 blob sizes of the target (255,
/// else 0), by the pixels' distance to the target.
cv::Mat nearbyInstances(const SegmentationScene& scene, const cv::Mat& other,
                        const cv::Mat& distance, float blob_px) {
  const cv::Mat& labels = scene.labels;
  const cv::Size size = labels.size();
  // Nearest distance of each instance to the target, pixels.
  std::vector<float> nearest(scene.obj_ids.size() + 1, std::numeric_limits<float>::infinity());
  for (int v = 0; v < size.height; ++v) {
    for (int u = 0; u < size.width; ++u) {
      if (!other.at<uint8_t>(v, u)) continue;
      float& d = nearest[labels.at<int>(v, u)];
      d = std::min(d, distance.at<float>(v, u));
    }
  }
  cv::Mat neighbours(size, CV_8UC1, cv::Scalar(0));
  for (int v = 0; v < size.height; ++v) {
    for (int u = 0; u < size.width; ++u) {
      const int l = labels.at<int>(v, u);
      if (other.at<uint8_t>(v, u) && nearest[l] < 2 * blob_px) neighbours.at<uint8_t>(v, u) = 255;
    }
  }
  return neighbours;
}

/// Confident false positives on other objects near the target, most likely next to it (0 to 1).
cv::Mat neighbourFiring(const SegmentationScene& scene, const SceneMasks& masks,
                        const RandomLayout& layout, const SegmentationNoiseParams& params) {
  cv::Mat distance;
  cv::distanceTransform(masks.target == 0, distance, cv::DIST_L2, 3);
  const cv::Mat neighbours = nearbyInstances(scene, masks.other, distance, params.blob_px);
  const cv::Mat toward_target = layout.neighbour_field - distance / (2 * params.blob_px);
  cv::Mat false_positive =
      softAbove(toward_target, upperQuantile(toward_target, neighbours, layout.neighbour_share));
  false_positive.setTo(0, neighbours == 0);
  return false_positive;
}

/// How much each pixel off the target looks like it (0 to 1): by colour similarity with an RGB
/// image, else 1 on the background.
cv::Mat lookalikeLevel(const SegmentationScene& scene, const cv::Mat& target,
                       float colour_tolerance) {
  const cv::Size size = scene.labels.size();
  cv::Mat lookalike(size, CV_32F, cv::Scalar(0));
  const cv::Scalar target_colour = scene.rgb.empty() ? cv::Scalar() : cv::mean(scene.rgb, target);
  for (int v = 0; v < size.height; ++v) {
    for (int u = 0; u < size.width; ++u) {
      if (target.at<uint8_t>(v, u)) continue;
      if (scene.rgb.empty()) {
        lookalike.at<float>(v, u) = scene.labels.at<int>(v, u) == 0 ? 1.0f : 0.0f;
        continue;
      }
      const cv::Vec3b c = scene.rgb.at<cv::Vec3b>(v, u);
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += (c[k] - target_colour[k]) * (c[k] - target_colour[k]);
      lookalike.at<float>(v, u) =
          static_cast<float>(std::exp(-d2 / (2.0 * colour_tolerance * colour_tolerance)));
    }
  }
  return lookalike;
}

/// False positives on pixels that look like the target, in the look-alike field's regions.
cv::Mat lookalikeFiring(const SegmentationScene& scene, const cv::Mat& target,
                        const RandomLayout& layout, const SegmentationNoiseParams& params) {
  const cv::Mat everywhere(scene.labels.size(), CV_8UC1, cv::Scalar(255));
  return lookalikeLevel(scene, target, params.colour_tolerance)
      .mul(softAbove(layout.lookalike_field,
                     upperQuantile(layout.lookalike_field, everywhere, params.lookalike_fraction)));
}

/// The map of an object among the scene's instances, before the noise: found where it is
/// visible, with false positives on neighbours and look-alikes.
cv::Mat presentObject(const SegmentationScene& scene, const SceneMasks& masks,
                      const RandomLayout& layout, const SegmentationNoiseParams& params) {
  const cv::Mat found = foundObject(masks.target, layout, params);
  const cv::Mat false_positive = neighbourFiring(scene, masks, layout, params);
  const cv::Mat lookalike = lookalikeFiring(scene, masks.target, layout, params);
  return cv::max(found, params.false_positive_level * cv::max(false_positive, lookalike));
}

/// The labels of the instances with at least one visible pixel, in increasing order.
std::vector<int> visibleLabels(const cv::Mat& labels) {
  std::set<int> seen;
  for (int v = 0; v < labels.rows; ++v) {
    const int* l = labels.ptr<int>(v);
    for (int u = 0; u < labels.cols; ++u) {
      if (l[u] > 0) seen.insert(l[u]);
    }
  }
  return {seen.begin(), seen.end()};
}

/// Class confusion: one visible instance's region found as the right class would be (bleeding,
/// missed regions), at a level below it; nothing when no instance is visible.
cv::Mat confusedObject(const cv::Mat& labels, const RandomLayout& layout,
                       const SegmentationNoiseParams& params, Rng& rng) {
  const std::vector<int> visible = visibleLabels(labels);
  const float level = std::min(1.0f, params.confusion_level * (0.75f + 0.5f * uniform01(rng)));
  if (visible.empty()) return cv::Mat::zeros(labels.size(), CV_32F);
  const int label = visible[uniformIndex(rng, static_cast<uint32_t>(visible.size()))];
  return foundObject(labels == label, layout, params) * level;
}

/// Up to `absent_blobs` Gaussian blobs of moderate probability anywhere in the image, each about
/// half a `blob_px` across.
cv::Mat noiseBlobs(cv::Size size, const SegmentationNoiseParams& params, Rng& rng) {
  cv::Mat blobs = cv::Mat::zeros(size, CV_32F);
  const int count =
      params.absent_blobs > 0 ? 1 + static_cast<int>(uniformIndex(rng, params.absent_blobs)) : 0;
  for (int k = 0; k < count; ++k) {
    const float cu = uniform01(rng) * size.width, cv = uniform01(rng) * size.height;
    const float sigma = params.blob_px * (0.2f + 0.2f * uniform01(rng));
    const float peak = std::min(1.0f, params.absent_blob_level * (0.6f + 0.8f * uniform01(rng)));
    const int reach = static_cast<int>(std::ceil(3 * sigma));
    for (int v = std::max(0, static_cast<int>(cv) - reach);
         v <= std::min(size.height - 1, static_cast<int>(cv) + reach); ++v) {
      float* b = blobs.ptr<float>(v);
      for (int u = std::max(0, static_cast<int>(cu) - reach);
           u <= std::min(size.width - 1, static_cast<int>(cu) + reach); ++u) {
        const float d2 = (u - cu) * (u - cu) + (v - cv) * (v - cv);
        b[u] = std::max(b[u], peak * std::exp(-d2 / (2 * sigma * sigma)));
      }
    }
  }
  return blobs;
}

/// The pixels of the visible instances of the target's look-alikes (255, else 0).
cv::Mat lookalikePixels(const SegmentationScene& scene, int target_obj_id) {
  cv::Mat pixels(scene.labels.size(), CV_8UC1, cv::Scalar(0));
  const auto lookalikes = scene.lookalikes.find(target_obj_id);
  if (lookalikes == scene.lookalikes.end()) return pixels;
  for (size_t i = 0; i < scene.obj_ids.size(); ++i) {
    if (lookalikes->second.count(scene.obj_ids[i]))
      pixels.setTo(255, scene.labels == static_cast<int>(i) + 1);
  }
  return pixels;
}

/// The map of an object that is not in the scene: its visible look-alikes found as the right class
/// would be, else a confusion or noise blobs (drawn from its own stream of `seed`, so present
/// objects' maps stay as they were), plus the preset's noise.
cv::Mat absentObject(const SegmentationScene& scene, int target_obj_id, const RandomLayout& layout,
                     const SegmentationNoiseParams& params, uint64_t seed) {
  Rng rng(streamSeed(seed, 0xab5e47));
  const cv::Mat lookalikes = lookalikePixels(scene, target_obj_id);
  if (cv::countNonZero(lookalikes) > 0) {
    const float level = params.lookalike_confusion_level * (0.75f + 0.5f * uniform01(rng));
    return foundObject(lookalikes, layout, params) * std::min(1.0f, level);
  }
  const bool confusion = uniform01(rng) < params.absent_confusion_share;
  return confusion ? confusedObject(scene.labels, layout, params, rng)
                   : noiseBlobs(scene.labels.size(), params, rng);
}

}  // namespace

const ParamSet<SegmentationNoiseParams>& SegmentationNoiseParams::schema() {
  using P = SegmentationNoiseParams;
  const ParamRange share = ParamRange::closed(0, 1);
  static const ParamSet<P> schema =
      ParamSet<P>()
          .add(&P::confidence, "confidence", "", share,
               "probability on an object pixel that is found")
          .add(&P::missed_fraction, "missed_fraction", "", share,
               "mean share of the object's visible pixels that are missed")
          .add(&P::missed_level, "missed_level", "", share, "probability left in a missed region")
          .add(&P::bleed_px, "bleed_px", "px", ParamRange::closed(0, 100),
               "spread of the map over the object's outline")
          .add(&P::neighbour_fraction, "neighbour_fraction", "", share,
               "mean share of each nearby other object that fires")
          .add(&P::lookalike_fraction, "lookalike_fraction", "", share,
               "share of the image where look-alike pixels may fire")
          .add(&P::colour_tolerance, "colour_tolerance", "", ParamRange::closed(1, 442),
               "RGB distance at which a pixel stops looking like the target")
          .add(&P::false_positive_level, "false_positive_level", "", share,
               "probability of a false-positive region")
          .add(&P::blob_px, "blob_px", "px", ParamRange::closed(1, 1000),
               "size of missed and false-positive regions")
          .add(&P::noise, "noise", "", share, "amplitude of the smooth low-level noise")
          .add(&P::absent_confusion_share, "absent_confusion_share", "", share,
               "share of absent targets whose map is a confusion with a visible object")
          .add(&P::confusion_level, "confusion_level", "", share,
               "mean probability on a confused object's region, relative to confidence")
          .add(&P::lookalike_confusion_level, "lookalike_confusion_level", "", share,
               "mean probability of an absent object's map on its visible look-alikes, relative "
               "to confidence")
          .add(&P::absent_blobs, "absent_blobs", "", ParamRange::closed(0, 100),
               "most blobs of an absent object's noise map")
          .add(&P::absent_blob_level, "absent_blob_level", "", share,
               "mean peak probability of a blob of an absent object's noise map");
  return schema;
}

void SegmentationNoiseParams::validate() const {
  schema().validate(*this,
                    [](const ParamInfo& info) { return "segmentation simulator: " + info.key; });
}

std::vector<std::string> segmentationPresetNames() {
  std::vector<std::string> names;
  for (const auto& [name, params] : presets()) names.push_back(name);
  return names;
}

SegmentationNoiseParams segmentationPreset(const std::string& name) {
  for (const auto& [preset, params] : presets()) {
    if (preset == name) return params;
  }
  throw InputError(fmt::format("unknown segmentation preset '{}'; known presets: {}", name,
                               fmt::join(segmentationPresetNames(), ", ")));
}

SegmentationSeeds keyframeSeeds(uint64_t object_seed, int frame, int period) {
  const int key = frame / period;
  return {streamSeed(object_seed, key), streamSeed(object_seed, key + 1),
          static_cast<float>(frame % period) / period};
}

cv::Mat simulateSegmentation(const SegmentationScene& scene, int target_obj_id,
                             const SegmentationNoiseParams& params, uint64_t seed) {
  return simulateSegmentation(scene, target_obj_id, params, SegmentationSeeds{seed, seed, 0});
}

cv::Mat simulateSegmentation(const SegmentationScene& scene, int target_obj_id,
                             const SegmentationNoiseParams& params,
                             const SegmentationSeeds& seeds) {
  params.validate();
  checkScene(scene);
  const SceneMasks masks = sceneMasks(scene, target_obj_id);
  const RandomLayout layout = drawLayout(scene.labels.size(), params, seeds);
  const bool absent =
      std::find(scene.obj_ids.begin(), scene.obj_ids.end(), target_obj_id) == scene.obj_ids.end();
  const uint64_t nearer = seeds.weight < 0.5f ? seeds.from : seeds.to;
  cv::Mat probability = absent ? absentObject(scene, target_obj_id, layout, params, nearer)
                               : presentObject(scene, masks, layout, params);
  probability += params.noise * layout.noise_field;
  return cv::min(cv::max(probability, 0.0f), 1.0f);
}

}  // namespace stocs
