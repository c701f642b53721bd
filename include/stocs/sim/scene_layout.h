#pragma once
// Random tabletop arrangements for generated scenes: objects resting on a support plane in stable
// poses, footprints apart (no interpenetration), and cameras looking down at the table from varied
// elevations. The table frame has z up and its origin on the table top at the arrangement's centre.

#include <Eigen/Geometry>
#include <vector>

#include "stocs/geometry/mesh.h"
#include "stocs/util/param_set.h"
#include "stocs/util/random.h"

namespace stocs {

/// Stable ways for a solid to rest on a plane: among the six orientations that put a model axis
/// straight down, those whose centre of mass lies over the convex hull of the contact points (at
/// least 1 mm inside), as rotations from the model frame to the table frame. Never empty: when no
/// orientation is stable the one with the centre of mass nearest to inside is kept.
std::vector<Eigen::Matrix3f> restingOrientations(const MeshData& mesh);

/// Centre of mass of a closed mesh of uniform density (of the vertices for a point model).
Eigen::Vector3f centreOfMass(const MeshData& mesh);

struct SceneLayoutParams {
  int objects = 4;             ///< dataset objects per scene (fewer when the table is full)
  int distractors = 2;         ///< shapes without ground truth among them
  float table_radius = 0.18f;  ///< object centres lie within this radius, metres
  float gap = 0.005f;          ///< minimum distance between two footprints, metres
  float min_distance = 0.55f, max_distance = 0.9f;       ///< camera to table centre, metres
  float min_elevation_deg = 30, max_elevation_deg = 75;  ///< camera angle above the table

  /// Key, range, unit and meaning of every field.
  static const ParamSet<SceneLayoutParams>& schema();
  /// Throws InputError naming the first value out of range, or a range whose ends are reversed.
  void validate() const;
  /// Throws InputError when a range's ends are reversed (the part of validate() no schema says).
  void checkOrder() const;
};

/// A packed bin (`stocs synth --packed-bin ID`): identical boxes of one object side by side in rows
/// and columns, every one of them a ground-truth instance, inside four thin walls.
struct PackedBinParams {
  int object = 0;      ///< object id of the boxes; 0: no bin, tabletop scenes
  int rows = 2;        ///< boxes across the bin
  int columns = 4;     ///< boxes along the bin
  float gap = 0.003f;  ///< between neighbouring boxes, metres

  /// Key, range, unit and meaning of every field.
  static const ParamSet<PackedBinParams>& schema();
};

struct PlacedObject {
  int obj_id = 0;  ///< dataset object id; 0 for a distractor
  MeshData mesh;   ///< metres
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();  ///< model to table frame
};

/// Places objects drawn from `models` (id and mesh; each used once while there are enough, in a
/// random order) and `params.distractors` random boxes and cylinders. An object that finds no free
/// place in 200 tries is left out.
std::vector<PlacedObject> arrangeObjects(const std::vector<std::pair<int, MeshData>>& models,
                                         const SceneLayoutParams& params, Rng& rng);

/// The packed bin of `params`: `rows` x `columns` instances of `mesh` (object `obj_id`), each
/// resting on its largest stable face, all the same way up, in a grid `gap` apart; each turned by a
/// random half turn about the vertical, and by a small yaw and shift that keep every pair of boxes
/// apart. Four walls 5 mm thick, 5 mm higher than the boxes and `gap` away from them, are
/// distractors (id 0). Centred on the table origin.
std::vector<PlacedObject> arrangePackedBin(int obj_id, const MeshData& mesh,
                                           const PackedBinParams& params, Rng& rng);

/// Whether object `moving` of `objects`, put at `pose` (model to table), keeps its footprint at
/// least `gap` metres from every other object's at its own pose.
bool footprintClear(const std::vector<PlacedObject>& objects, size_t moving,
                    const Eigen::Isometry3f& pose, float gap);

/// A camera pose (table frame to camera optical frame: z forward, y down) at a random distance,
/// elevation and azimuth, looking at a point near the table centre.
Eigen::Isometry3f randomCameraPose(const SceneLayoutParams& params, Rng& rng);

/// The pose (table frame to camera optical frame) of a camera at `eye` looking at `target` with
/// zero roll: image x to the right, y down towards the table.
Eigen::Isometry3f cameraLookingAt(const Eigen::Vector3f& eye, const Eigen::Vector3f& target);

}  // namespace stocs
