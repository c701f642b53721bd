#include "stocs/object_model.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "stocs/error.h"
#include "stocs/normals.h"
#include "stocs/surface_sampling.h"

namespace stocs {
namespace {

constexpr uint64_t kSamplingSeed = 0x5707C5;  // fixed: a model always gives the same samples

/// Dense oriented points describing the whole surface, before thinning.
OrientedPoints denseSurface(const MeshData& mesh, const ModelSamplingParams& params, float radius,
                            Rng& rng) {
  if (!mesh.isMesh()) {
    OrientedPoints dense{mesh.vertices,
                         estimatePcaNormals(mesh.vertices, params.normal_neighbours)};
    VisibilityOrientationParams vis;
    vis.viewpoints = params.orientation_viewpoints;
    orientNormalsByVisibility(dense.points, dense.normals, vis);
    return dense;
  }
  // About 20 dense samples per Poisson disc keeps the thinned set even.
  const double area = meshArea(mesh);
  const size_t count =
      static_cast<size_t>(std::clamp(20.0 * area / (radius * radius), 20000.0, 400000.0));
  OrientedPoints dense = sampleMeshSurface(mesh, count, rng);
  // Winding gives consistent normals; only a mesh wound inside-out needs flipping as a whole.
  std::vector<Eigen::Vector3f> check = dense.normals;
  VisibilityOrientationParams vis;
  vis.viewpoints = params.orientation_viewpoints;
  if (2 * static_cast<size_t>(orientNormalsByVisibility(dense.points, check, vis)) > check.size()) {
    for (Eigen::Vector3f& n : dense.normals) n = -n;
  }
  return dense;
}

}  // namespace

void ModelSamplingParams::validate() const {
  if (!(sampling_ratio >= 0.005f && sampling_ratio <= 0.5f)) {
    throw InputError(
        fmt::format("model sampling ratio {} is outside [0.005, 0.5]", sampling_ratio));
  }
  if (normal_neighbours < 4 || normal_neighbours > 200) {
    throw InputError(fmt::format("normal neighbours {} is outside [4, 200]", normal_neighbours));
  }
  if (orientation_viewpoints < 6 || orientation_viewpoints > 10000) {
    throw InputError(
        fmt::format("orientation viewpoints {} is outside [6, 10000]", orientation_viewpoints));
  }
}

ObjectModel prepareModel(const MeshData& mesh, const ModelSamplingParams& params) {
  params.validate();
  if (mesh.vertices.empty()) throw InputError("model has no vertices");
  Rng rng(kSamplingSeed);
  ObjectModel model;
  model.diameter = pointSetDiameter(mesh.vertices);
  model.sampling_radius = params.sampling_ratio * model.diameter;
  const OrientedPoints dense = denseSurface(mesh, params, model.sampling_radius, rng);
  if (dense.points.empty()) throw InputError("model mesh has no triangle with a positive area");

  std::vector<size_t> kept = poissonDiscSubset(dense.points, model.sampling_radius, rng);
  while (kept.size() > kMaxModelSamples) {  // only for absurdly fine ratios on huge point models
    model.sampling_radius *= 1.25f;
    kept = poissonDiscSubset(dense.points, model.sampling_radius, rng);
  }
  model.points.reserve(kept.size());
  model.normals.reserve(kept.size());
  for (size_t i : kept) {
    model.points.push_back(dense.points[i]);
    model.normals.push_back(dense.normals[i].normalized());
  }
  return model;
}

}  // namespace stocs
