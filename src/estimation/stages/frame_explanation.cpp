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
  std::vector<int> pixels;  ///< unique indices into the PixelTable's area
  std::vector<float> map;   ///< the pose's object's probability at each pixel
  const std::string* object = nullptr;
  float confidence = 0;
  bool alive = true;  ///< still accepted
};

/// A pose's confirmed samples as squares of pixels (centre u, v and half side): within the sample
/// spacing, so that poses on one surface claim the same pixels although their samples project
/// onto different ones. `box` bounds them in the image.
struct Splats {
  std::vector<cv::Vec3i> squares;
  cv::Rect box;
};

Splats splatsOf(const FramePose& p, const FreeSpaceCheck& visibility) {
  const CameraIntrinsics& camera = visibility.camera();
  const ObjectModel& model = *p.model;
  Splats out;
  visibility.visit(model, p.pose->pose, [&](size_t i, int u, int v, SampleView view) {
    if (view != SampleView::kConfirmed) return;
    const float z = (p.pose->pose * model.points[i]).z();
    const int h = static_cast<int>(std::lround(camera.fx * model.sampling_radius / z));
    out.squares.emplace_back(u, v, h);
    out.box |= cv::Rect(u - h, v - h, 2 * h + 1, 2 * h + 1);
  });
  out.box &= cv::Rect(0, 0, camera.width, camera.height);
  return out;
}

/// The image part where claims overlap, and the last claim that marked each of its pixels, so
/// that a claim lists a pixel once.
struct PixelTable {
  explicit PixelTable(const cv::Rect& area) : area(area), marked_by(area.area(), -1) {}
  cv::Rect area;
  std::vector<int> marked_by;
};

/// Claim `id`: the pixels of its splats (all within the table's area) and its map there.
Claim claimOf(const FramePose& p, const Splats& splats, int id, PixelTable& table) {
  Claim c;
  c.object = &p.object;
  c.confidence = p.pose->confidence;
  const cv::Rect& area = table.area;
  for (const cv::Vec3i& s : splats.squares) {
    const int u = s[0], v = s[1], h = s[2];
    for (int y = std::max(area.y, v - h); y <= std::min(area.br().y - 1, v + h); ++y) {
      for (int x = std::max(area.x, u - h); x <= std::min(area.br().x - 1, u + h); ++x) {
        const int pixel = (y - area.y) * area.width + (x - area.x);
        if (table.marked_by[pixel] == id) continue;
        table.marked_by[pixel] = id;
        c.pixels.push_back(pixel);
        c.map.push_back(p.probability->at<float>(y, x));
      }
    }
  }
  return c;
}

/// The pixels of a pose's splats within `roi` (CV_8UC1 of its size, 255).
cv::Mat splatMask(const Splats& splats, const cv::Rect& roi) {
  cv::Mat mask(roi.size(), CV_8UC1, cv::Scalar(0));
  for (const cv::Vec3i& s : splats.squares) {
    const int h = s[2];
    const cv::Rect square = cv::Rect(s[0] - h, s[1] - h, 2 * h + 1, 2 * h + 1) & roi;
    if (!square.empty()) mask(square - roi.tl()).setTo(255);
  }
  return mask;
}

/// Whether an accepted pose of `object` other than pose i covers more than `share` of `mask`,
/// pose i's pixels (within its splats' box).
bool posedThere(const std::vector<FramePose>& poses, const std::vector<Splats>& splats, size_t i,
                const cv::Mat& mask, const std::string& object, float share) {
  const int pixels = cv::countNonZero(mask);
  for (size_t j = 0; j < poses.size(); ++j) {
    if (j == i || poses[j].object != object || !poses[j].pose->accepted) continue;
    if ((splats[i].box & splats[j].box).empty()) continue;
    const cv::Mat both = mask & splatMask(splats[j], splats[i].box);
    if (cv::countNonZero(both) > share * pixels) return true;
  }
  return false;
}

/// The object whose map holds pose i's splatted pixels more strongly than the pose's own object's
/// map, on the mean over those pixels (a map's noise averages out), and has no pose over more than
/// `share` of them (where it has, the poses compete instead: explainedShare); or null.
const std::string* claimedByMaps(const std::vector<FramePose>& poses,
                                 const std::vector<Splats>& splats, size_t i,
                                 const std::vector<ObjectMap>& maps, float share) {
  const FramePose& p = poses[i];
  const cv::Rect& box = splats[i].box;
  if (box.empty()) return nullptr;
  const cv::Mat mask = splatMask(splats[i], box);
  const double mine = cv::mean((*p.probability)(box), mask)[0];
  const std::string* by = nullptr;
  double strongest = mine;
  for (const ObjectMap& m : maps) {
    if (m.object == p.object) continue;
    const double theirs = cv::mean((*m.probability)(box), mask)[0];
    if (theirs > strongest && !posedThere(poses, splats, i, mask, m.object, share)) {
      by = &m.object;
      strongest = theirs;
    }
  }
  return by;
}

/// Rejects the accepted poses whose surface the map of an object without a pose there holds more
/// strongly (claimedByMaps).
void rejectClaimedByMaps(std::vector<FramePose>& poses, const std::vector<Splats>& splats,
                         const std::vector<ObjectMap>& maps, float share) {
  std::vector<const std::string*> claimed(poses.size(), nullptr);
  for (size_t i = 0; i < poses.size(); ++i) {
    if (poses[i].pose->accepted) claimed[i] = claimedByMaps(poses, splats, i, maps, share);
  }
  for (size_t i = 0; i < poses.size(); ++i) {
    if (!claimed[i]) continue;
    poses[i].pose->accepted = false;
    poses[i].pose->rejection = fmt::format("claimed by the map of {}", *claimed[i]);
  }
}

/// Which poses' splats overlap another's (by their boxes): only those can explain or be explained.
std::vector<char> overlapping(const std::vector<Splats>& splats) {
  std::vector<char> out(splats.size(), 0);
  for (size_t i = 0; i < splats.size(); ++i) {
    for (size_t j = i + 1; j < splats.size(); ++j) {
      if ((splats[i].box & splats[j].box).empty()) continue;
      out[i] = out[j] = 1;
    }
  }
  return out;
}

/// Every claim on each pixel of the area: (claim, index of the pixel in the claim's list).
struct ClaimsPerPixel {
  std::vector<int> start;  ///< pixel p's claims are entries [start[p], start[p + 1])
  std::vector<std::pair<int, int>> entries;
};

ClaimsPerPixel claimsPerPixel(const std::vector<Claim>& claims, int pixels) {
  ClaimsPerPixel out;
  out.start.assign(pixels + 1, 0);
  for (const Claim& c : claims) {
    for (int p : c.pixels) ++out.start[p + 1];
  }
  for (int p = 0; p < pixels; ++p) out.start[p + 1] += out.start[p];
  out.entries.resize(out.start.back());
  std::vector<int> next(out.start.begin(), out.start.end() - 1);
  for (int i = 0; i < static_cast<int>(claims.size()); ++i) {
    for (size_t k = 0; k < claims[i].pixels.size(); ++k) {
      out.entries[next[claims[i].pixels[k]]++] = {i, static_cast<int>(k)};
    }
  }
  return out;
}

/// How strongly claim `c` holds its k-th pixel against a claim of `other_object`: its map there;
/// times its confidence against another object when the maps do not name objects. Two poses of
/// one object share its map, and a network's maps say which object is where, so the map decides;
/// maps from depth alone mark every region of an object's size alike, and then the pose that fits
/// better holds it.
float hold(const Claim& c, int k, const std::string& other_object, bool maps_name_objects) {
  if (maps_name_objects || *c.object == other_object) return c.map[k];
  return c.map[k] * c.confidence;
}

/// The share of a claim's pixels that another living claim confirms and holds at least as
/// strongly (hold), and the claim explaining most of them.
struct Explained {
  float share = 0;
  int by = -1;
};

Explained explainedShare(const std::vector<Claim>& claims, int i, const ClaimsPerPixel& table,
                         bool maps_name_objects) {
  std::vector<int> by(claims.size(), 0);
  int explained = 0;
  const Claim& mine = claims[i];
  for (size_t k = 0; k < mine.pixels.size(); ++k) {
    const int p = mine.pixels[k];
    int best = -1;
    float best_hold = 0;
    for (int e = table.start[p]; e < table.start[p + 1]; ++e) {
      const auto [j, kj] = table.entries[e];
      if (j == i || !claims[j].alive) continue;
      const float theirs = hold(claims[j], kj, *mine.object, maps_name_objects);
      if (theirs < hold(mine, static_cast<int>(k), *claims[j].object, maps_name_objects)) continue;
      if (best < 0 || theirs > best_hold) {
        best = j;
        best_hold = theirs;
      }
    }
    if (best < 0) continue;
    ++explained;
    ++by[best];
  }
  if (explained == 0) return {};
  const auto most = std::max_element(by.begin(), by.end());
  return {static_cast<float>(explained) / mine.pixels.size(), static_cast<int>(most - by.begin())};
}

/// The living claim most explained by others above the limit, the lower confidence on a tie
/// (claim -1 if none), and how it is explained. Most redundant first: a pose slid across two
/// boxes goes before the two right poses, each of which it covers by half.
struct MostExplained {
  int claim = -1;
  Explained explained;
};

/// Also writes each living claim's share to `shares` (indexed as `claims`).
MostExplained mostExplained(const std::vector<Claim>& claims, const ClaimsPerPixel& table,
                            float max_share, bool maps_name_objects, std::vector<float>& shares) {
  MostExplained worst;
  for (int i = 0; i < static_cast<int>(claims.size()); ++i) {
    if (!claims[i].alive) continue;
    const Explained e = explainedShare(claims, i, table, maps_name_objects);
    shares[i] = e.share;
    if (e.share <= max_share) continue;
    const bool tie = worst.claim >= 0 && e.share == worst.explained.share;
    if (worst.claim < 0 || e.share > worst.explained.share ||
        (tie && claims[i].confidence < claims[worst.claim].confidence)) {
      worst = {i, e};
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
          .flag("--max-explained-share")
          .add(&FrameExplanationParams::search_again, "search_again",
               "an object whose every pose others explain is searched for again elsewhere")
          .flag("--search-again");
  return schema;
}

void FrameExplanationParams::validate() const {
  schema().validate(*this);
}

std::vector<ExplainedPose> explainPoses(std::vector<FramePose>& poses,
                                        const FreeSpaceCheck& visibility,
                                        const FrameExplanationParams& params,
                                        bool maps_name_objects,
                                        const std::vector<ObjectMap>& maps) {
  params.validate();
  std::vector<ExplainedPose> explained;
  if (!params.enabled) return explained;
  for (FramePose& p : poses) {
    if (p.pose->accepted) p.pose->evidence.explained = 0;  // counted again below where it overlaps
  }
  std::vector<Splats> splats;
  for (const FramePose& p : poses) {
    splats.push_back(p.pose->accepted ? splatsOf(p, visibility) : Splats{});
  }
  if (maps_name_objects) rejectClaimedByMaps(poses, splats, maps, params.max_explained_share);
  // Only poses whose confirmed pixels may overlap compete, in a table of the area they cover.
  for (size_t i = 0; i < poses.size(); ++i) {
    if (!poses[i].pose->accepted) splats[i] = Splats{};
  }
  const std::vector<char> overlaps = overlapping(splats);
  cv::Rect area;
  for (size_t i = 0; i < poses.size(); ++i) {
    if (overlaps[i]) area |= splats[i].box;
  }
  if (area.empty()) return explained;
  PixelTable table(area);
  std::vector<Claim> claims;
  for (size_t i = 0; i < poses.size(); ++i) {
    const int id = static_cast<int>(i);
    claims.push_back(overlaps[i] ? claimOf(poses[i], splats[i], id, table) : Claim{});
    claims.back().alive = poses[i].pose->accepted;
  }
  const ClaimsPerPixel per_pixel = claimsPerPixel(claims, area.area());
  std::vector<float> shares(claims.size(), 0.0f);
  for (;;) {
    const MostExplained worst =
        mostExplained(claims, per_pixel, params.max_explained_share, maps_name_objects, shares);
    if (worst.claim < 0) break;
    const int by = worst.explained.by;
    claims[worst.claim].alive = false;
    explained.push_back({static_cast<size_t>(worst.claim), static_cast<size_t>(by)});
    InstancePose& rejected = *poses[worst.claim].pose;
    rejected.accepted = false;
    rejected.evidence.explained = worst.explained.share;
    rejected.rejection = fmt::format("explained by {} {}", poses[by].object, poses[by].instance);
  }
  // The last count's shares: those of the poses left.
  for (size_t i = 0; i < poses.size(); ++i) {
    if (claims[i].alive) poses[i].pose->evidence.explained = shares[i];
  }
  return explained;
}

cv::Mat confirmedArea(const std::vector<FramePose>& poses, const std::vector<bool>& counts,
                      const FreeSpaceCheck& visibility) {
  const CameraIntrinsics& camera = visibility.camera();
  cv::Mat area(camera.height, camera.width, CV_8UC1, cv::Scalar(0));
  const cv::Rect image(0, 0, camera.width, camera.height);
  for (size_t i = 0; i < poses.size(); ++i) {
    if (counts[i] && poses[i].pose->accepted) {
      area |= splatMask(splatsOf(poses[i], visibility), image);
    }
  }
  return area;
}

}  // namespace stocs
