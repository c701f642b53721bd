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
  std::vector<int> pixels;  ///< unique indices into the image
  std::vector<float> map;   ///< the pose's object's probability at each pixel
  float confidence = 0;
  bool alive = true;  ///< still accepted
};

/// Per pixel of the image, the two living claims with the highest map there (-1: none), ties
/// included: enough to tell whether another claim explains a pixel at least as well as a given
/// one. Also the last claim that marked each pixel, so that a claim lists a pixel once. Allocated
/// once per frame; only the claims' pixels are ever reset.
struct PixelTable {
  explicit PixelTable(int pixel_count)
      : first(pixel_count, -1),
        second(pixel_count, -1),
        first_map(pixel_count, 0),
        second_map(pixel_count, 0),
        marked_by(pixel_count, -1) {}
  std::vector<int> first, second;
  std::vector<float> first_map, second_map;
  std::vector<int> marked_by;
};

/// The pixels within the sample spacing of the pose's confirmed samples: poses on one surface
/// then claim the same pixels although their samples project onto different ones.
std::vector<int> confirmedPixels(const FramePose& p, int id, const FreeSpaceCheck& visibility,
                                 PixelTable& table) {
  const CameraIntrinsics& camera = visibility.camera();
  std::vector<int> pixels;
  const ObjectModel& model = *p.model;
  visibility.visit(model, p.pose->pose, [&](size_t i, int u, int v, SampleView view) {
    if (view != SampleView::kConfirmed) return;
    const float z = (p.pose->pose * model.points[i]).z();
    const int h = static_cast<int>(std::lround(camera.fx * model.sampling_radius / z));
    for (int y = std::max(0, v - h); y <= std::min(camera.height - 1, v + h); ++y) {
      for (int x = std::max(0, u - h); x <= std::min(camera.width - 1, u + h); ++x) {
        const int pixel = y * camera.width + x;
        if (table.marked_by[pixel] == id) continue;
        table.marked_by[pixel] = id;
        pixels.push_back(pixel);
      }
    }
  });
  return pixels;
}

Claim claimOf(const FramePose& p, int id, const FreeSpaceCheck& visibility, PixelTable& table) {
  Claim c;
  c.alive = p.pose->accepted;
  if (!c.alive) return c;  // a rejected pose explains nothing
  c.pixels = confirmedPixels(p, id, visibility, table);
  c.map.reserve(c.pixels.size());
  for (int k : c.pixels)
    c.map.push_back(p.probability->at<float>(k / p.probability->cols, k % p.probability->cols));
  c.confidence = p.pose->confidence;
  return c;
}

/// Fills `t`'s two best claims of every pixel some claim holds.
void rankClaims(const std::vector<Claim>& claims, PixelTable& t) {
  for (const Claim& c : claims) {
    for (int p : c.pixels) t.first[p] = t.second[p] = -1;
  }
  for (int i = 0; i < static_cast<int>(claims.size()); ++i) {
    if (!claims[i].alive) continue;
    for (size_t k = 0; k < claims[i].pixels.size(); ++k) {
      const int p = claims[i].pixels[k];
      const float m = claims[i].map[k];
      if (t.first[p] < 0 || m > t.first_map[p]) {
        t.second[p] = t.first[p];
        t.second_map[p] = t.first_map[p];
        t.first[p] = i;
        t.first_map[p] = m;
      } else if (t.second[p] < 0 || m > t.second_map[p]) {
        t.second[p] = i;
        t.second_map[p] = m;
      }
    }
  }
}

/// The share of a claim's pixels that another living claim confirms with at least as high a map
/// (the network says that object is there as much or more), and the claim explaining most of them.
struct Explained {
  float share = 0;
  int by = -1;
};

Explained explainedShare(const std::vector<Claim>& claims, int i, const PixelTable& t) {
  std::vector<int> by(claims.size(), 0);
  int explained = 0;
  for (size_t k = 0; k < claims[i].pixels.size(); ++k) {
    const int p = claims[i].pixels[k];
    const bool first = t.first[p] == i;
    const int other = first ? t.second[p] : t.first[p];
    const float other_map = first ? t.second_map[p] : t.first_map[p];
    if (other < 0 || other_map < claims[i].map[k]) continue;
    ++explained;
    ++by[other];
  }
  if (explained == 0) return {};
  const auto most = std::max_element(by.begin(), by.end());
  return {static_cast<float>(explained) / claims[i].pixels.size(),
          static_cast<int>(most - by.begin())};
}

/// The living claim most explained by others above the limit, the lower confidence on a tie
/// (first: -1 if none), and the claim explaining most of it. Most redundant first: a pose slid
/// across two boxes goes before the two right poses, each of which it covers by half.
std::pair<int, int> mostExplained(const std::vector<Claim>& claims, const PixelTable& t,
                                  float max_share) {
  std::pair<int, int> worst{-1, -1};
  float worst_share = 0;
  for (int i = 0; i < static_cast<int>(claims.size()); ++i) {
    if (!claims[i].alive) continue;
    const Explained e = explainedShare(claims, i, t);
    if (e.share <= max_share) continue;
    const bool tie = worst.first >= 0 && e.share == worst_share;
    if (worst.first < 0 || e.share > worst_share ||
        (tie && claims[i].confidence < claims[worst.first].confidence)) {
      worst = {i, e.by};
      worst_share = e.share;
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
  PixelTable table(visibility.camera().width * visibility.camera().height);
  std::vector<Claim> claims;
  claims.reserve(poses.size());
  for (const FramePose& p : poses) {
    claims.push_back(claimOf(p, static_cast<int>(claims.size()), visibility, table));
  }
  for (;;) {
    rankClaims(claims, table);
    const auto [worst, by] = mostExplained(claims, table, params.max_explained_share);
    if (worst < 0) return;
    claims[worst].alive = false;
    InstancePose& rejected = *poses[worst].pose;
    rejected.accepted = false;
    rejected.rejection = fmt::format("explained by {} {}", poses[by].object, poses[by].instance);
  }
}

}  // namespace stocs
