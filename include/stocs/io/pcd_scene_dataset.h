#pragma once
// Registration scenes in the layout of PCL's test data (an organized PCD scene, a PCD model and a
// gt.json with the model's pose in the scene) turned into one-image BOP datasets, so that the
// evaluation tools treat them like any other dataset.

#include <filesystem>

namespace stocs {

/// True for a folder holding gt.json with "T_scene_from_model" and no models/ folder.
bool isPcdSceneFolder(const std::filesystem::path& dir);

/// Writes the scene of `dir` as a BOP dataset in `out` (created; existing files are replaced):
/// scene 0, image 0, object 1.
///  * depth/000000.png: the cloud's z, 16-bit in 0.1 mm units (depth_scale 0.1);
///    rgb/000000.png from the cloud's colours;
///  * scene_camera.json: cam_K recovered from the cloud (intrinsicsFromCloud), as the files have
///    no intrinsics;
///  * models/obj_000001.ply (mm, moved so that its bounding box centre is the origin, as in BOP)
///    and models_info.json (diameter); scene_gt.json from T_scene_from_model and that move;
///  * mask_visib/000000_000000.png: the pixels whose point lies within 0.1 mm of a model point
///    placed by the ground truth (the model is a crop of the scene), for simulated segmentations.
/// There is no prob/ map. gt.json "units" may be "m" or "mm". Returns the number of mask pixels.
/// Throws InputError naming the file and the problem.
int convertPcdSceneToBop(const std::filesystem::path& dir, const std::filesystem::path& out);

}  // namespace stocs
