#pragma once
// The project's own object models, made by code (no third-party data): two boxes, a cylinder, a
// mug, a bowl and an asymmetric block. `stocs meshes` writes them to meshes/ (PLY in mm with a BOP
// models_info.json); `stocs synth` puts them in generated scenes; tests use them directly.
// Apart from them, textured objects whose shape is (nearly) symmetric and whose print is not, for
// scenes where colour or a mug's handle alone tells the poses apart (`stocs synth --catalogue`),
// and look-alikes of standard objects, for scenes where a network confuses them.

#include <string>
#include <vector>

#include "stocs/geometry/mesh.h"
#include "stocs/io/bop_dataset.h"

namespace stocs {

struct CatalogueObject {
  int id = 0;        ///< BOP object id (obj_{id:06d}.ply)
  std::string name;  ///< what the shape is, e.g. "mug"
  MeshData mesh;     ///< metres, closed, outward winding, origin at the bounding-box centre
  /// Symmetries in the BOP format (translations in mm; diameter_mm left 0, it comes from the mesh):
  /// for a textured object only those that keep the print in place, as BOP counts them.
  BopObjectInfo symmetries;
  /// The part of the mesh that alone breaks the symmetry of the rest (a mug's handle), in the
  /// mesh's frame; empty when there is none.
  MeshData handle = {};
  /// Objects of similar shape and size that a network confuses with this one (lookalikes.h).
  std::vector<int> lookalikes = {};
};

/// Every catalogue object, ids 1..N. Deterministic: the same meshes on every call.
std::vector<CatalogueObject> objectCatalogue();

/// Vertex-coloured objects, ids 7..9 (after objectCatalogue()'s): a nearly square carton with a
/// label on one face, a can with a print on one side, and a mug with a print opposite its handle.
/// None has a symmetry that keeps its print; the mug's `handle` is set.
std::vector<CatalogueObject> texturedCatalogue();

/// Look-alikes of two standard objects, ids 10..11: a box within 20% per side of the box (id 1)
/// and a can the size of the mug's body (id 4), each declaring that object as its look-alike.
std::vector<CatalogueObject> lookalikeCatalogue();

/// The catalogue selections of `stocs synth --catalogue`: "standard" (objectCatalogue()),
/// "textured" (texturedCatalogue()), "all" (both) and "lookalike" (objectCatalogue() and
/// lookalikeCatalogue()).
const std::vector<std::string>& catalogueSelectionNames();
/// The objects of a selection; throws InputError naming the selections for an unknown name.
std::vector<CatalogueObject> catalogueSelection(const std::string& name);

/// The colour (RGB, alpha 255) object `id` is painted with where its mesh has none: eight distinct
/// colours, later ids reuse them. The scenes show it and the written model files carry it, as a
/// user's coloured meshes would.
Rgba plainColour(int id);

/// A 10 x 6 x 4 cm box with a 4 x 4 x 3 cm block on one corner of its top (origin at the centre of
/// the large box): no symmetry, so every pose is distinguishable. Catalogue object 6, recentred.
MeshData asymmetricMesh();

}  // namespace stocs
