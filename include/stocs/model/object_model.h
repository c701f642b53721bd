#pragma once
// An object model ready for matching: evenly spaced surface samples with outward unit normals.

#include <Eigen/Core>
#include <vector>

#include "stocs/geometry/mesh.h"
#include "stocs/util/param_set.h"

namespace stocs {

struct ModelSamplingParams {
  /// Poisson-disc radius of the samples as a fraction of the object diameter. 0.04 gives about
  /// 5 mm on a 12 cm object, the paper's PPF distance step.
  float sampling_ratio = 0.04f;
  /// Neighbours for PCA normals of point-only models.
  int normal_neighbours = 16;
  /// Viewpoints for outward orientation of point-only models.
  int orientation_viewpoints = 96;

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<ModelSamplingParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

struct ObjectModel {
  /// Metres, in the model frame, in random order: any prefix is an unbiased subsample (the
  /// coarse-to-fine verification relies on this).
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;  ///< unit, outward
  float diameter = 0;                    ///< of the input surface, metres
  float sampling_radius = 0;             ///< Poisson-disc radius used, metres
  /// The surface's colour at each sample (mesh.h's Colour, NaN where unknown); empty when the model
  /// file has no colour.
  std::vector<Colour> colours;
  /// Whether the samples are even over the surface's area (a mesh's). A point model's are not: a
  /// scan's density varies and holes stay holes, so the objective, a sum over samples, is not the
  /// share of the visible surface explained.
  bool even_sampling = true;

  size_t size() const { return points.size(); }
  bool hasColour() const { return !colours.empty(); }
};

/// Mean of the model's samples: the point about which the refinement's steps turn, and the near
/// symmetries' axes pass.
Eigen::Vector3f sampleCentre(const ObjectModel& model);

/// At most this many samples, so that sample indices fit in 16 bits in the PPF map.
constexpr size_t kMaxModelSamples = 65535;

/// Samples a mesh's surface (area-weighted, then Poisson-disc) with face normals, or thins a point
/// model (Poisson-disc) after estimating and orienting its normals. Deterministic. Samples carry
/// the colour interpolated at them (meshes) or their point's colour (point models).
ObjectModel prepareModel(const MeshData& mesh, const ModelSamplingParams& params);

}  // namespace stocs
