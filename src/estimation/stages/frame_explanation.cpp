#include "stocs/estimation/stages/frame_explanation.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>

#include "stocs/estimation/pose_estimate.h"

namespace stocs {
namespace {

/// The measured pixels one accepted pose confirms, and its object's map there.
struct Claim {
  std::vector<int> pixels;  ///< sorted, unique indices into the image
  std::vector<float> map;   ///< the pose's object's probability at each pixel
  float confidence = 0;
  bool alive = true;  ///< still accepted
};

/// The pixels within the sample spacing of the pose's confirmed samples: poses on one surface
/// then claim the same pixels although their samples project onto different ones.
std::vector<int> confirmedPixels(const FramePose& p, const FreeSpaceCheck& visibility) {
  const CameraIntrinsics& camera = visibility.camera();
  std::vector<int> pixels;
  const ObjectModel& model = *p.model;
  visibility.visit(model, p.pose->pose, [&](size_t i, int u, int v, SampleView view) {
    if (view != SampleView::kConfirmed) return;
    const float z = (p.pose->pose * model.points[i]).z();
    const int h = static_cast<int>(std::lround(camera.fx * model.sampling_radius / z));
    for (int y = std::max(0, v - h); y <= std::min(camera.height - 1, v + h); ++y) {
      for (int x = std::max(0, u - h); x <= std::min(camera.width - 1, u + h); ++x) {
        pixels.push_back(y * camera.width + x);
      }
    }
  });
  std::sort(pixels.begin(), pixels.end());
  pixels.erase(std::unique(pixels.begin(), pixels.end()), pixels.end());
  return pixels;
}

Claim claimOf(const FramePose& p, const FreeSpaceCheck& visibility) {
  Claim c;
  c.pixels = confirmedPixels(p, visibility);
  c.map.reserve(c.pixels.size());
  for (int k : c.pixels)
    c.map.push_back(p.probability->at<float>(k / p.probability->cols, k % p.probability->cols));
  c.confidence = p.pose->confidence;
  c.alive = p.pose->accepted;
  return c;
}

/// Whether claim a's pixel (its map value `map_a`) explains it better than claim b's: the map
/// first (the network's word on which object is there), then the confidence, then the order.
bool explainsBetter(const std::vector<Claim>& claims, int a, float map_a, int b, float map_b) {
  if (map_a != map_b) return map_a > map_b;
  if (claims[a].confidence != claims[b].confidence) {
    return claims[a].confidence > claims[b].confidence;
  }
  return a < b;
}

/// Per pixel, the living claim that explains it best (-1: none).
std::vector<int> owners(const std::vector<Claim>& claims, int pixel_count) {
  std::vector<int> owner(pixel_count, -1);
  std::vector<float> owner_map(pixel_count, 0);
  for (int i = 0; i < static_cast<int>(claims.size()); ++i) {
    if (!claims[i].alive) continue;
    for (size_t k = 0; k < claims[i].pixels.size(); ++k) {
      const int p = claims[i].pixels[k];
      const float m = claims[i].map[k];
      if (owner[p] < 0 || explainsBetter(claims, i, m, owner[p], owner_map[p])) {
        owner[p] = i;
        owner_map[p] = m;
      }
    }
  }
  return owner;
}

/// A claim's pixels that others own, in all and by the claim owning most of them.
struct Explained {
  float share = 0;
  int by = -1;
};

Explained explainedShare(const std::vector<Claim>& claims, int i, const std::vector<int>& owner) {
  std::vector<int> by(claims.size(), 0);
  int lost = 0;
  for (int p : claims[i].pixels) {
    if (owner[p] == i) continue;
    ++lost;
    ++by[owner[p]];
  }
  if (claims[i].pixels.empty()) return {};
  const auto most = std::max_element(by.begin(), by.end());
  return {static_cast<float>(lost) / claims[i].pixels.size(),
          lost > 0 ? static_cast<int>(most - by.begin()) : -1};
}

/// The living claim of lowest confidence explained above the limit by others (first: -1 if none).
std::pair<int, int> worstExplained(const std::vector<Claim>& claims, const std::vector<int>& owner,
                                   float max_share) {
  std::pair<int, int> worst{-1, -1};
  for (int i = 0; i < static_cast<int>(claims.size()); ++i) {
    if (!claims[i].alive) continue;
    const Explained e = explainedShare(claims, i, owner);
    if (e.share <= max_share) continue;
    if (worst.first < 0 || claims[i].confidence <= claims[worst.first].confidence) {
      worst = {i, e.by};
    }
  }
  return worst;
}

}  // namespace

const ParamSet<FrameExplanationParams>& FrameExplanationParams::schema() {
  static const ParamSet<FrameExplanationParams> schema =
      ParamSet<FrameExplanationParams>()
          .add(&FrameExplanationParams::enabled, "enabled",
               "choose a frame's poses jointly: each measured point explained by one pose")
          .flag("--frame-explanation")
          .add(&FrameExplanationParams::max_explained_share, "max_explained_share", "",
               ParamRange::closed(0, 1),
               "a pose more of whose confirmed surface other poses explain is rejected")
          .flag("--max-explained-share");
  return schema;
}

void FrameExplanationParams::validate() const {
  schema().validate(*this);
}

void explainPoses(std::vector<FramePose>& poses, const FreeSpaceCheck& visibility,
                  const FrameExplanationParams& params) {
  params.validate();
  if (!params.enabled) return;
  std::vector<Claim> claims;
  claims.reserve(poses.size());
  for (const FramePose& p : poses) claims.push_back(claimOf(p, visibility));
  const int pixel_count = visibility.camera().width * visibility.camera().height;
  for (;;) {
    const std::vector<int> owner = owners(claims, pixel_count);
    const auto [worst, by] = worstExplained(claims, owner, params.max_explained_share);
    if (worst < 0) return;
    claims[worst].alive = false;
    InstancePose& rejected = *poses[worst].pose;
    rejected.accepted = false;
    rejected.rejection = fmt::format("explained by {} {}", poses[by].object, poses[by].instance);
  }
}

}  // namespace stocs
