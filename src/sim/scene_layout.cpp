#include "stocs/sim/scene_layout.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>

#include "stocs/sim/shape_meshes.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

constexpr float kPi = static_cast<float>(M_PI);

float uniformIn(Rng& rng, float lo, float hi) {
  return lo + (hi - lo) * uniform01(rng);
}

/// Convex hull of the x-y projection of points, in mm.
std::vector<cv::Point2f> footprintMm(const std::vector<Eigen::Vector3f>& points) {
  std::vector<cv::Point2f> xy;
  for (const Eigen::Vector3f& p : points) xy.emplace_back(p.x() * 1000, p.y() * 1000);
  std::vector<cv::Point2f> hull;
  cv::convexHull(xy, hull);
  return hull;
}

/// Whether two convex footprints are at least `gap_mm` apart along one of their edge normals
/// (separating axes): then they neither overlap nor come closer than the gap.
bool separated(const std::vector<cv::Point2f>& a, const std::vector<cv::Point2f>& b, float gap_mm) {
  for (const std::vector<cv::Point2f>* polygon : {&a, &b}) {
    const std::vector<cv::Point2f>& p = *polygon;
    for (size_t i = 0; i < p.size(); ++i) {
      const cv::Point2f edge = p[(i + 1) % p.size()] - p[i];
      const cv::Point2f axis(-edge.y, edge.x);
      const float length = std::hypot(axis.x, axis.y);
      if (!(length > 0)) continue;
      float a_lo = 1e30f, a_hi = -1e30f, b_lo = 1e30f, b_hi = -1e30f;
      for (const cv::Point2f& q : a) {
        a_lo = std::min(a_lo, axis.dot(q) / length);
        a_hi = std::max(a_hi, axis.dot(q) / length);
      }
      for (const cv::Point2f& q : b) {
        b_lo = std::min(b_lo, axis.dot(q) / length);
        b_hi = std::max(b_hi, axis.dot(q) / length);
      }
      if (a_hi + gap_mm <= b_lo || b_hi + gap_mm <= a_lo) return true;
    }
  }
  return false;
}

MeshData randomDistractor(Rng& rng) {
  if (uniform01(rng) < 0.5f) {
    return boxMesh(
        {uniformIn(rng, 0.03f, 0.12f), uniformIn(rng, 0.03f, 0.12f), uniformIn(rng, 0.03f, 0.12f)});
  }
  const float radius = uniformIn(rng, 0.02f, 0.05f), height = uniformIn(rng, 0.04f, 0.15f);
  MeshData cylinder = cylinderMesh(radius, height, 32);
  for (Eigen::Vector3f& v : cylinder.vertices) v.z() -= height / 2;
  return cylinder;
}

}  // namespace

Eigen::Vector3f centreOfMass(const MeshData& mesh) {
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  double volume = 0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    // The tetrahedron (origin, a, b, c): signed volume and centroid.
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(),
                          b = mesh.vertices[t[1]].cast<double>(),
                          c = mesh.vertices[t[2]].cast<double>();
    const double v = a.dot(b.cross(c)) / 6;
    volume += v;
    weighted += v * (a + b + c) / 4;
  }
  if (std::abs(volume) > 1e-12) return (weighted / volume).cast<float>();
  Eigen::Vector3f mean = Eigen::Vector3f::Zero();
  for (const Eigen::Vector3f& p : mesh.vertices) mean += p;
  return mean / static_cast<float>(std::max<size_t>(1, mesh.vertices.size()));
}

std::vector<Eigen::Matrix3f> restingOrientations(const MeshData& mesh) {
  const std::vector<Eigen::Matrix3f> axis_down = {
      Eigen::Matrix3f::Identity(),                                               // -z down
      Eigen::AngleAxisf(kPi, Eigen::Vector3f::UnitX()).toRotationMatrix(),       // +z down
      Eigen::AngleAxisf(kPi / 2, Eigen::Vector3f::UnitY()).toRotationMatrix(),   // +x down
      Eigen::AngleAxisf(-kPi / 2, Eigen::Vector3f::UnitY()).toRotationMatrix(),  // -x down
      Eigen::AngleAxisf(-kPi / 2, Eigen::Vector3f::UnitX()).toRotationMatrix(),  // +y down
      Eigen::AngleAxisf(kPi / 2, Eigen::Vector3f::UnitX()).toRotationMatrix(),   // -y down
  };
  const Eigen::Vector3f com = centreOfMass(mesh);
  const float tolerance = 0.01f * pointSetDiameter(mesh.vertices);
  std::vector<Eigen::Matrix3f> stable;
  Eigen::Matrix3f best = axis_down[0];
  double best_margin = -1e9;
  for (const Eigen::Matrix3f& r : axis_down) {
    float lowest = std::numeric_limits<float>::infinity();
    for (const Eigen::Vector3f& v : mesh.vertices) lowest = std::min(lowest, (r * v).z());
    std::vector<Eigen::Vector3f> contact;
    for (const Eigen::Vector3f& v : mesh.vertices) {
      if ((r * v).z() < lowest + tolerance) contact.push_back(r * v);
    }
    const std::vector<cv::Point2f> hull = footprintMm(contact);
    const Eigen::Vector3f c = r * com;
    // Millimetres inside the contact hull (negative outside).
    const double margin =
        hull.size() < 3 ? -1e6
                        : cv::pointPolygonTest(hull, cv::Point2f(c.x() * 1000, c.y() * 1000), true);
    if (margin >= 1.0) stable.push_back(r);
    if (margin > best_margin) {
      best_margin = margin;
      best = r;
    }
  }
  if (stable.empty()) stable.push_back(best);
  return stable;
}

const ParamSet<SceneLayoutParams>& SceneLayoutParams::schema() {
  using P = SceneLayoutParams;
  static const ParamSet<P> schema =
      ParamSet<P>()
          .add(&P::objects, "objects", "", ParamRange::closed(1, 100),
               "dataset objects per scene (fewer when the table is full)")
          .flag("--objects")
          .add(&P::distractors, "distractors", "", ParamRange::closed(0, 100),
               "shapes without ground truth per scene")
          .flag("--distractors")
          .add(&P::table_radius, "table_radius", "m", ParamRange::closed(0, 5),
               "object centres lie within this radius of the table centre")
          .flag("--table-radius")
          .add(&P::gap, "gap", "m", ParamRange::closed(0, 0.5),
               "least distance between two objects' footprints")
          .flag("--gap")
          .add(&P::min_distance, "min_distance", "m", ParamRange::closed(0.1, 10),
               "least camera distance to the table centre")
          .flag("--min-distance")
          .add(&P::max_distance, "max_distance", "m", ParamRange::closed(0.1, 10),
               "greatest camera distance to the table centre")
          .flag("--max-distance")
          .add(&P::min_elevation_deg, "min_elevation_deg", "deg", ParamRange::closed(5, 85),
               "least camera elevation above the table")
          .flag("--min-elevation")
          .add(&P::max_elevation_deg, "max_elevation_deg", "deg", ParamRange::closed(5, 85),
               "greatest camera elevation above the table")
          .flag("--max-elevation");
  return schema;
}

void SceneLayoutParams::validate() const {
  schema().validate(*this, [](const ParamInfo& info) { return "scene layout: " + info.key; });
  checkOrder();
}

void SceneLayoutParams::checkOrder() const {
  if (max_distance < min_distance) {
    throw InputError(fmt::format("scene layout: max_distance {} m is below min_distance {} m",
                                 max_distance, min_distance));
  }
  if (max_elevation_deg < min_elevation_deg) {
    throw InputError(fmt::format("scene layout: max_elevation_deg {} is below min_elevation_deg {}",
                                 max_elevation_deg, min_elevation_deg));
  }
}

std::vector<PlacedObject> arrangeObjects(const std::vector<std::pair<int, MeshData>>& models,
                                         const SceneLayoutParams& params, Rng& rng) {
  params.validate();
  std::vector<size_t> order(models.size());
  std::iota(order.begin(), order.end(), 0);
  for (size_t i = order.size(); i > 1; --i) {
    std::swap(order[i - 1], order[uniformIndex(rng, static_cast<uint32_t>(i))]);
  }
  std::vector<PlacedObject> wanted;
  for (int k = 0; k < params.objects && !models.empty(); ++k) {
    const auto& [id, mesh] = models[order[k % models.size()]];
    wanted.push_back({id, mesh, Eigen::Isometry3f::Identity()});
  }
  for (int k = 0; k < params.distractors; ++k) {
    wanted.push_back({0, randomDistractor(rng), Eigen::Isometry3f::Identity()});
  }

  std::vector<PlacedObject> placed;
  std::vector<std::vector<cv::Point2f>> footprints;
  for (PlacedObject& object : wanted) {
    const std::vector<Eigen::Matrix3f> rests = restingOrientations(object.mesh);
    for (int attempt = 0; attempt < 200; ++attempt) {
      const Eigen::Matrix3f rotation =
          Eigen::AngleAxisf(uniformIn(rng, 0, 2 * kPi), Eigen::Vector3f::UnitZ()) *
          rests[uniformIndex(rng, static_cast<uint32_t>(rests.size()))];
      const float radius = params.table_radius * std::sqrt(uniform01(rng));
      const float angle = uniformIn(rng, 0, 2 * kPi);
      std::vector<Eigen::Vector3f> moved;
      float lowest = std::numeric_limits<float>::infinity();
      for (const Eigen::Vector3f& v : object.mesh.vertices) {
        moved.push_back(rotation * v);
        lowest = std::min(lowest, moved.back().z());
      }
      const Eigen::Vector3f offset(radius * std::cos(angle), radius * std::sin(angle), -lowest);
      for (Eigen::Vector3f& v : moved) v += offset;
      const std::vector<cv::Point2f> footprint = footprintMm(moved);
      const bool free = std::all_of(footprints.begin(), footprints.end(), [&](const auto& other) {
        return separated(footprint, other, params.gap * 1000);
      });
      if (!free) continue;
      object.pose.linear() = rotation;
      object.pose.translation() = offset;
      footprints.push_back(footprint);
      placed.push_back(std::move(object));
      break;
    }
  }
  return placed;
}

bool footprintClear(const std::vector<PlacedObject>& objects, size_t moving,
                    const Eigen::Isometry3f& pose, float gap) {
  std::vector<Eigen::Vector3f> moved;
  for (const Eigen::Vector3f& v : objects[moving].mesh.vertices) moved.push_back(pose * v);
  const std::vector<cv::Point2f> footprint = footprintMm(moved);
  for (size_t i = 0; i < objects.size(); ++i) {
    if (i == moving) continue;
    std::vector<Eigen::Vector3f> other;
    for (const Eigen::Vector3f& v : objects[i].mesh.vertices) other.push_back(objects[i].pose * v);
    if (!separated(footprint, footprintMm(other), gap * 1000)) return false;
  }
  return true;
}

Eigen::Isometry3f randomCameraPose(const SceneLayoutParams& params, Rng& rng) {
  const float elevation =
      uniformIn(rng, params.min_elevation_deg, params.max_elevation_deg) * kPi / 180;
  const float azimuth = uniformIn(rng, 0, 2 * kPi);
  const float distance = uniformIn(rng, params.min_distance, params.max_distance);
  const Eigen::Vector3f target(uniformIn(rng, -0.03f, 0.03f), uniformIn(rng, -0.03f, 0.03f), 0.03f);
  const Eigen::Vector3f eye =
      target + distance * Eigen::Vector3f(std::cos(elevation) * std::cos(azimuth),
                                          std::cos(elevation) * std::sin(azimuth),
                                          std::sin(elevation));
  return cameraLookingAt(eye, target);
}

Eigen::Isometry3f cameraLookingAt(const Eigen::Vector3f& eye, const Eigen::Vector3f& target) {
  // Optical frame: z toward the target, x to the right, y down (towards the table at zero roll).
  const Eigen::Vector3f z = (target - eye).normalized();
  const Eigen::Vector3f x = z.cross(Eigen::Vector3f::UnitZ()).normalized();
  const Eigen::Vector3f y = z.cross(x);
  Eigen::Isometry3f camera_in_table = Eigen::Isometry3f::Identity();
  camera_in_table.linear().col(0) = x;
  camera_in_table.linear().col(1) = y;
  camera_in_table.linear().col(2) = z;
  camera_in_table.translation() = eye;
  return camera_in_table.inverse();
}

}  // namespace stocs

namespace stocs {
namespace {

/// The stable resting orientation of `mesh` with the lowest height (its largest face down).
Eigen::Matrix3f flattestRest(const MeshData& mesh) {
  Eigen::Matrix3f flattest = Eigen::Matrix3f::Identity();
  float least = std::numeric_limits<float>::infinity();
  for (const Eigen::Matrix3f& r : restingOrientations(mesh)) {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (const Eigen::Vector3f& v : mesh.vertices) {
      lo = std::min(lo, (r * v).z());
      hi = std::max(hi, (r * v).z());
    }
    if (hi - lo < least) {
      least = hi - lo;
      flattest = r;
    }
  }
  return flattest;
}

/// The axis-aligned bounds of `mesh` turned by `r`.
Eigen::AlignedBox3f turnedBounds(const MeshData& mesh, const Eigen::Matrix3f& r) {
  Eigen::AlignedBox3f box;
  for (const Eigen::Vector3f& v : mesh.vertices) box.extend(r * v);
  return box;
}

/// A wall of `size` standing on the table with its centre above (x, y).
PlacedObject binWall(const Eigen::Vector3f& size, float x, float y) {
  PlacedObject wall{0, boxMesh(size), Eigen::Isometry3f::Identity()};
  wall.pose.translation() = Eigen::Vector3f(x, y, size.z() / 2);
  return wall;
}

/// The four walls around an inside of `inner` (x, y) metres, `height` high.
std::vector<PlacedObject> binWalls(const Eigen::Vector2f& inner, float height) {
  constexpr float kThickness = 0.005f;
  const float x = (inner.x() + kThickness) / 2, y = (inner.y() + kThickness) / 2;
  const float outer_x = inner.x() + 2 * kThickness;
  return {binWall({outer_x, kThickness, height}, 0, y),
          binWall({outer_x, kThickness, height}, 0, -y),
          binWall({kThickness, inner.y(), height}, x, 0),
          binWall({kThickness, inner.y(), height}, -x, 0)};
}

}  // namespace

const ParamSet<PackedBinParams>& PackedBinParams::schema() {
  using P = PackedBinParams;
  static const ParamSet<P> schema =
      ParamSet<P>()
          .add(&P::object, "object", "", ParamRange::closed(0, 1000000),
               "object id of the boxes of a packed bin, every one a ground-truth instance; 0: "
               "tabletop scenes")
          .flag("--packed-bin")
          .add(&P::rows, "rows", "", ParamRange::closed(1, 20), "boxes across the packed bin")
          .flag("--bin-rows")
          .add(&P::columns, "columns", "", ParamRange::closed(1, 20), "boxes along the packed bin")
          .flag("--bin-columns")
          .add(&P::gap, "gap", "m", ParamRange::closed(0, 0.05),
               "gap between neighbouring boxes of the packed bin")
          .flag("--bin-gap");
  return schema;
}

std::vector<PlacedObject> arrangePackedBin(int obj_id, const MeshData& mesh,
                                           const PackedBinParams& params, Rng& rng) {
  const Eigen::Matrix3f rest = flattestRest(mesh);
  const Eigen::AlignedBox3f bounds = turnedBounds(mesh, rest);
  const Eigen::Vector3f size = bounds.sizes();
  const Eigen::Vector2f pitch(size.x() + params.gap, size.y() + params.gap);
  // Each box moves by at most 0.43 gap (yaw at its corners, shift), so two stay apart.
  const float max_yaw = params.gap / (2 * size.head<2>().norm());
  const float max_shift = params.gap / 8;
  std::vector<PlacedObject> placed;
  for (int row = 0; row < params.rows; ++row) {
    for (int column = 0; column < params.columns; ++column) {
      const float half_turn = uniform01(rng) < 0.5f ? kPi : 0.0f;
      const float yaw = half_turn + uniformIn(rng, -max_yaw, max_yaw);
      const Eigen::Vector3f cell((column - (params.columns - 1) / 2.0f) * pitch.x(),
                                 (row - (params.rows - 1) / 2.0f) * pitch.y(), 0);
      const Eigen::Vector3f shift(uniformIn(rng, -max_shift, max_shift),
                                  uniformIn(rng, -max_shift, max_shift), 0);
      PlacedObject box{obj_id, mesh, Eigen::Isometry3f::Identity()};
      box.pose.linear() = Eigen::AngleAxisf(yaw, Eigen::Vector3f::UnitZ()) * rest;
      // The box's centre at the cell's, its bottom on the table.
      box.pose.translation() = cell + shift -
                               Eigen::AngleAxisf(yaw, Eigen::Vector3f::UnitZ()) * bounds.center() +
                               Eigen::Vector3f(0, 0, size.z() / 2);
      placed.push_back(std::move(box));
    }
  }
  const Eigen::Vector2f inner(params.columns * pitch.x() + params.gap,
                              params.rows * pitch.y() + params.gap);
  for (PlacedObject& wall : binWalls(inner, size.z() + 0.005f)) placed.push_back(std::move(wall));
  return placed;
}

}  // namespace stocs
