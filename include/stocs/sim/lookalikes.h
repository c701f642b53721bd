#pragma once
// Look-alike objects: pairs of objects of similar shape and size (boxes within 20% per side, a can
// and a mug's body) that a segmentation network confuses. A generated dataset whose catalogue
// declares such pairs lists them in `models/lookalikes.json`; the segmentation simulator then gives
// an absent object the map of its present look-alike (segmentation_simulator.h).

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <set>
#include <vector>

#include "stocs/sim/object_catalogue.h"

namespace stocs {

/// The look-alikes of each object id, both ways (a pair {a, b} lists b under a and a under b).
using Lookalikes = std::map<int, std::set<int>>;

/// The pairs the catalogue objects declare (CatalogueObject::lookalikes) among themselves; a
/// look-alike that is not in `objects` is left out.
Lookalikes catalogueLookalikes(const std::vector<CatalogueObject>& objects);

/// `models/lookalikes.json` of a BOP dataset at `root`.
std::filesystem::path lookalikesPath(const std::filesystem::path& root);

/// Writes `{"pairs": [[a, b], ...]}` (a < b, in increasing order). Throws InputError when the
/// file cannot be written.
void writeLookalikes(const std::filesystem::path& file, const Lookalikes& lookalikes);

/// The pairs of a lookalikes.json; none when the file does not exist. Throws InputError naming the
/// file for malformed JSON, a pair that is not two different positive object ids, or a missing
/// "pairs" list.
Lookalikes readLookalikes(const std::filesystem::path& file);

/// Whether two boxes' side lengths, each sorted, are within `tolerance` (0.2: 20%) of each other
/// per side, relative to the larger of the two.
bool boxesLookAlike(Eigen::Vector3f a, Eigen::Vector3f b, float tolerance = 0.2f);

}  // namespace stocs
