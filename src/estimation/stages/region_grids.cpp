#include "stocs/estimation/stages/region_grids.h"

namespace stocs {

RegionGrids::RegionGrids(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& region,
                         float radius)
    : points_(points),
      radius_(radius),
      has_regions_(!region.empty()),
      empty_(points, std::vector<uint32_t>{}, radius) {
  if (!has_regions_) {
    of(-1);  // every query takes the grid of all points: built at once
    return;
  }
  for (size_t i = 0; i < region.size(); ++i) {
    if (region[i] >= 0) regions_[region[i]].members.push_back(static_cast<uint32_t>(i));
  }
}

const NeighbourhoodGrid& RegionGrids::of(int region) const {
  if (region < 0 || !has_regions_) {
    std::call_once(all_.once, [&] { all_.grid = NeighbourhoodGrid(points_, radius_); });
    return all_.grid;
  }
  const auto it = regions_.find(region);
  if (it == regions_.end()) return empty_;
  const Lazy& lazy = it->second;
  std::call_once(lazy.once, [&] { lazy.grid = NeighbourhoodGrid(points_, lazy.members, radius_); });
  return lazy.grid;
}

}  // namespace stocs
