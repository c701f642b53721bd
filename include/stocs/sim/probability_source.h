#pragma once
// Where the per-object probability maps of a BOP frame come from: the dataset's real network maps
// (`prob/`), or the soft-segmentation simulator where a frame has none. `stocs estimate --prob` and
// `stocs bench` select a source by its spec string.

#include <memory>
#include <string>

#include "stocs/io/bop_dataset.h"

namespace cv {
class Mat;
}

namespace stocs {

class ProbabilitySource {
 public:
  virtual ~ProbabilitySource() = default;
  /// The spec this source was made from ("real", "sim:PRESET", ...).
  virtual std::string spec() const = 0;
  /// Whether a map exists (or can be produced) for the object in the image.
  virtual bool available(int scene_id, int im_id, int obj_id) const = 0;
  /// The map as CV_32FC1 in [0, 1]; throws InputError naming the file or the problem.
  virtual cv::Mat load(int scene_id, int im_id, int obj_id) const = 0;
  /// Whether its maps say which object is where (Frame::maps_name_objects).
  virtual bool namesObjects() const { return true; }
};

/// What the specs mean, for help texts.
std::string probabilitySourceHelp();

/// "real": the dataset's prob/ maps only; "sim:PRESET": the real map where prob/ has one, else the
/// segmentation simulator with that preset on the frame's visible ground-truth masks (see
/// GroundTruthMasks), for any object with a model: one that the frame's ground truth does not hold
/// gets the simulator's absent-object map; "simonly:PRESET": always simulated; "onnx:MODEL": the
/// segmentation network in the ONNX file MODEL on the frame's rgb/ image. Throws InputError
/// for an unknown spec or preset, listing the known ones. `seed` makes simulated maps reproducible;
/// the source keeps the last frame's masks, so it is not for use from several threads at once.
/// "onnx:SETTINGS.yaml": the network and settings a YAML file gives (makeNetworkProbabilitySource).
/// "geometric": from the frame's depth image alone, the union of the regions that can hold the
/// object by its model's size (geometric_segmentation.h), for any object with a model. "whole": no
/// segmentation, every pixel 1 (the whole scene), for any object with a model.
std::unique_ptr<ProbabilitySource> makeProbabilitySource(const std::string& spec,
                                                         const BopDataset& dataset, uint64_t seed);

}  // namespace stocs
