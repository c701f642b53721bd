#pragma once
// BOP's targets file (`test_targets_bop19.json`): a JSON list of {scene_id, im_id, obj_id,
// inst_count}, the (image, object) pairs a method is asked to estimate and how many instances of
// the object the image holds. This project also writes and reads `inst_count: 0`: an object that
// is not in the image, whose right answer is no pose.

#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

namespace stocs {

/// One object in one image. Ordered and compared by (scene, image, object) only.
struct BopTarget {
  int scene_id = 0;
  int im_id = 0;
  int obj_id = 0;
  int inst_count = 1;  ///< instances in the image; 0: the object is absent

  bool operator<(const BopTarget& o) const {
    return std::tie(scene_id, im_id, obj_id) < std::tie(o.scene_id, o.im_id, o.obj_id);
  }
  bool operator==(const BopTarget& o) const { return !(*this < o) && !(o < *this); }
};

/// Parses the text of a targets file; `name` (the file) prefixes every error. Throws InputError
/// naming the entry and the problem: invalid JSON, not a list, an entry that is not an object, a
/// missing key, a value that is not a non-negative integer (obj_id: positive), or an entry that
/// repeats an earlier (scene, image, object).
std::vector<BopTarget> parseBopTargets(const std::string& text, const std::string& name);

/// Reads a targets file (see parseBopTargets); throws InputError naming a file it cannot open.
std::vector<BopTarget> readBopTargets(const std::filesystem::path& file);

/// Writes a targets file, one entry per line, in the given order. Throws InputError naming the
/// file when it cannot be written.
void writeBopTargets(const std::filesystem::path& file, const std::vector<BopTarget>& targets);

}  // namespace stocs
