#pragma once
// 2D boxes from files: a detector's output in the BOP challenge's 2D detection format, and the
// visible boxes of a BOP scene's ground truth (scene_gt_info.json's bbox_visib).

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "stocs/io/segmentation_inputs.h"

namespace stocs {

/// Boxes per (scene id, image id).
using FrameBoxes = std::map<std::pair<int, int>, std::vector<BoxDetection>>;

/// A JSON list of {scene_id, image_id, category_id, bbox: [x, y, width, height], score} (pixels;
/// further keys, such as BOP's "time", are ignored); category_id is the object id. Throws
/// InputError naming `name`, the entry and the problem: invalid JSON, not a list, a missing key, a
/// bbox that is not 4 finite numbers with a positive size, a score outside [0, 1].
FrameBoxes parseBoxDetections(const std::string& text, const std::string& name);
/// parseBoxDetections of a file; throws InputError naming the file when it cannot be read.
FrameBoxes readBoxDetections(const std::filesystem::path& file);

/// scene_gt_info.json's `bbox_visib` of every instance, per image id, in scene_gt.json's order
/// (an instance with no visible pixel has a box of width or height 0 or less, as BOP writes it).
/// Throws InputError naming the file, the image and the instance of a malformed entry.
std::map<int, std::vector<cv::Rect2f>> readVisibleBoxes(const std::filesystem::path& file);

}  // namespace stocs
