#pragma once
// The project's own object models, made by code (no third-party data): two boxes, a cylinder, a
// mug, a bowl and an asymmetric block. `stocs meshes` writes them to meshes/ (PLY in mm with a BOP
// models_info.json); `stocs synth` puts them in generated scenes; tests use them directly.

#include <string>
#include <vector>

#include "stocs/geometry/mesh.h"
#include "stocs/io/bop_dataset.h"

namespace stocs {

struct CatalogueObject {
  int id = 0;        ///< BOP object id (obj_{id:06d}.ply)
  std::string name;  ///< what the shape is, e.g. "mug"
  MeshData mesh;     ///< metres, closed, outward winding, origin at the bounding-box centre
  /// Symmetries in the BOP format (translations in mm; diameter_mm left 0, it comes from the mesh).
  BopObjectInfo symmetries;
};

/// Every catalogue object, ids 1..N. Deterministic: the same meshes on every call.
std::vector<CatalogueObject> objectCatalogue();

/// A 10 x 6 x 4 cm box with a 4 x 4 x 3 cm block on one corner of its top (origin at the centre of
/// the large box): no symmetry, so every pose is distinguishable. Catalogue object 6, recentred.
MeshData asymmetricMesh();

}  // namespace stocs
