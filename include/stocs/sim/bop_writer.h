#pragma once
// Writing datasets in the BOP layout that BopDataset reads (see bop_dataset.h for the units):
// models with their models_info.json, and the per-scene JSON files of generated scenes.

#include <filesystem>
#include <map>
#include <vector>

#include "stocs/io/bop_dataset.h"
#include "stocs/sim/object_catalogue.h"

namespace stocs {

/// Writes each object as `obj_{id:06d}.ply` (mm, 0.1 um resolution; an object without colour in
/// its plain colour, as the scenes show it) and `models_info.json`
/// (diameter, bounding box and symmetries, mm) into `models_dir`, which must exist. The bytes
/// depend only on the meshes, so regenerating gives the same files. Throws InputError naming a file
/// that cannot be written.
void writeModels(const std::filesystem::path& models_dir,
                 const std::vector<CatalogueObject>& objects);

/// Visibility of one ground-truth instance, as in BOP's scene_gt_info.json.
struct BopGtInfo {
  long px_count_all = 0;    ///< pixels of the object's silhouette without occlusion
  long px_count_visib = 0;  ///< pixels where it is visible
  float visib_fract = 0;    ///< px_count_visib / px_count_all (0 for an empty silhouette)
  int bbox_visib[4] = {-1, -1, -1, -1};  ///< x, y, width, height of the visible pixels
};

/// How much of a ground-truth instance's handle (a mug's) an image shows: the part whose view alone
/// tells the pose of an otherwise symmetric shape (scene_handles.json, this project's own file).
struct HandleVisibility {
  int gt_index = 0;  ///< the instance's entry in the image's scene_gt.json list
  int obj_id = 0;
  long px_count_all = 0;    ///< pixels of the handle drawn alone
  long px_count_visib = 0;  ///< of those, pixels where the handle is the visible surface
  /// At least half of the handle's pixels visible.
  bool visible() const { return px_count_all > 0 && 2 * px_count_visib >= px_count_all; }
};

/// scene_camera.json, scene_gt.json and scene_gt_info.json of a scene, keyed by image id.
void writeSceneCameras(const std::filesystem::path& file,
                       const std::map<int, BopFrameCamera>& cameras);
void writeSceneGroundTruth(const std::filesystem::path& file,
                           const std::map<int, std::vector<BopGtInstance>>& gt);
void writeSceneGtInfo(const std::filesystem::path& file,
                      const std::map<int, std::vector<BopGtInfo>>& info);
/// scene_handles.json: per image id, a list of {gt_index, obj_id, px_count_all, px_count_visib,
/// handle_visible}.
void writeSceneHandles(const std::filesystem::path& file,
                       const std::map<int, std::vector<HandleVisibility>>& handles);

}  // namespace stocs
