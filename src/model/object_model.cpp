#include "stocs/model/object_model.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "stocs/geometry/normals.h"
#include "stocs/geometry/surface_sampling.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

constexpr uint64_t kSamplingSeed = 0x5707C5;  // fixed: a model always gives the same samples

/// Dense oriented points describing the whole surface, before thinning.
OrientedPoints denseSurface(const MeshData& mesh, const ModelSamplingParams& params, float radius,
                            Rng& rng) {
  if (!mesh.isMesh()) {
    OrientedPoints dense{
        mesh.vertices, estimatePcaNormals(mesh.vertices, params.normal_neighbours), {}};
    for (const auto& rgba : mesh.colours) dense.colours.push_back(toColour(rgba));
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

const ParamSet<ModelSamplingParams>& ModelSamplingParams::schema() {
  static const ParamSet<ModelSamplingParams> schema =
      ParamSet<ModelSamplingParams>()
          .add(&ModelSamplingParams::sampling_ratio, "sampling_ratio", "",
               ParamRange::closed(0.005, 0.5),
               "Poisson-disc radius of the model samples, fraction of the diameter")
          .flag("--model-sampling")
          .add(&ModelSamplingParams::normal_neighbours, "normal_neighbours", "",
               ParamRange::closed(4, 200), "point models: neighbours for PCA normals")
          .add(&ModelSamplingParams::orientation_viewpoints, "orientation_viewpoints", "",
               ParamRange::closed(6, 10000),
               "point models: viewpoints that orient the normals outwards");
  return schema;
}

void ModelSamplingParams::validate() const {
  schema().validate(*this);
}

Eigen::Vector3f sampleCentre(const ObjectModel& model) {
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  for (const Eigen::Vector3f& q : model.points) centre += q;
  return centre / static_cast<float>(std::max<size_t>(1, model.size()));
}

ObjectModel prepareModel(const MeshData& mesh, const ModelSamplingParams& params) {
  params.validate();
  if (mesh.vertices.empty()) throw InputError("model has no vertices");
  if (mesh.hasColour() && mesh.colours.size() != mesh.vertices.size()) {
    throw InputError(fmt::format("model has {} vertex colours for {} vertices", mesh.colours.size(),
                                 mesh.vertices.size()));
  }
  Rng rng(kSamplingSeed);
  ObjectModel model;
  model.diameter = pointSetDiameter(mesh.vertices);
  model.sampling_radius = params.sampling_ratio * model.diameter;
  model.even_sampling = mesh.isMesh();
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
    if (!dense.colours.empty()) model.colours.push_back(dense.colours[i]);
  }
  return model;
}

}  // namespace stocs
