#pragma once
// The StoCS node's configuration file (YAML): the objects (model, unit scale, symmetries, rviz
// mesh), the inputs and their synchronization, the outputs, the model cache, and every estimation
// parameter of the core (stocs::PipelineParams, keys named after its fields). config/default.yaml
// lists every key with its default.

#include <filesystem>
#include <string>
#include <vector>

#include "stocs/estimation/pipeline.h"
#include "stocs/io/segmentation_inputs.h"
#include "stocs/model/object_symmetries.h"
#include "stocs/segmentation/geometric_segmentation.h"
#include "stocs/tracking/tracking_params.h"
#include "stocs_ros/common/stamp_synchronizer.h"

namespace stocs_ros {

struct ObjectConfig {
  std::string name;             ///< topic and TF name component
  int id = 0;                   ///< numeric id in the outputs (default: position in the list + 1)
  std::filesystem::path model;  ///< model file (PLY, PCD, OBJ, STL, DAE, glTF, GLB), resolved
  float unit_scale = 0.001f;    ///< model units to metres
  std::string mesh_url;         ///< rviz mesh_resource; empty: markers show the model samples
  float mesh_scale = 0.001f;    ///< mesh units to metres (default: unit_scale)
  stocs::ObjectSymmetries symmetries;  ///< in metres
};

enum class DepthSource { kCloud, kDepthImage };
/// kGeometric: no segmentation input; each object's map comes from the depth alone
/// (stocs::GeometricSegmenter, input.geometric).
enum class ProbabilitySource { kPerObject, kMultichannel, kLabels, kMasks, kBoxes, kGeometric };

struct InputConfig {
  DepthSource depth = DepthSource::kCloud;
  ProbabilitySource probability = ProbabilitySource::kPerObject;
  /// kMultichannel: the object name of each channel, in order; "-" marks a channel to ignore.
  std::vector<std::string> channels;
  double uint16_scale = 10000;  ///< mono16 probability = value / uint16_scale
  bool boundary = false;        ///< subscribe ~boundary for instance regions
  /// Subscribe ~rgb, the colour image registered with the depth (REP 118), for telling a coloured
  /// model's pose from its shape alternatives; a cloud's rgb field serves without it.
  bool colour = false;
  /// kLabels, kMasks, kBoxes: the object name of each class id in order (class 0 first); "-"
  /// marks a class to ignore. Empty: an object's class id is its `id`.
  std::vector<std::string> labels;
  bool label_confidence = false;  ///< kLabels: also wait for ~label_confidence
  /// How labels, masks and boxes become probability maps.
  stocs::SegmentationInputParams segmentation;
  /// kGeometric: how the depth is segmented into object candidates.
  stocs::GeometricSegmentationParams geometric;
  SyncParams sync;

  /// Whether the probability maps come from labels, masks or boxes.
  bool segmentationForm() const;
  /// The input keys but `channels` (a list), for the file reader and the docs.
  static const stocs::ParamSet<InputConfig>& schema();
};

struct OutputConfig {
  /// Frame of every pose output (REP 105: base_link, odom, map, ...); empty: the input's frame.
  std::string frame;
  double transform_timeout = 0.1;  ///< seconds to wait for the input-to-output transform
  std::string frame_prefix;        ///< TF child frame = frame_prefix + object name
  bool tf = true;
  bool markers = true;
  bool estimate_on_frames = true;  ///< false: estimate only on ~estimate calls

  static const stocs::ParamSet<OutputConfig>& schema();
};

struct NodeConfig {
  std::filesystem::path file;  ///< the file it was read from
  std::vector<ObjectConfig> objects;
  InputConfig input;
  OutputConfig output;
  std::string model_cache_setting;    ///< as written: a folder, "" (the default one) or "none"
  std::filesystem::path model_cache;  ///< the folder it names; empty: no cache
  stocs::PipelineParams estimation;
  /// The node tracks by default (a camera stream); the core and `stocs estimate` detect.
  stocs::TrackingParams tracking = stocs::TrackingParams::forStream();

  /// Every key of the file but the objects and input.channels (lists): keys, ranges, meanings.
  static const stocs::ParamSet<NodeConfig>& schema();

  /// The class id of object `object` in labels, masks and boxes (input.labels, else its id).
  int classOf(size_t object) const;
  /// Index of the object called `name`, or -1.
  int objectIndex(const std::string& name) const;
  /// The configured object names, comma-separated.
  std::string objectNames() const;
};

/// Reads and checks a configuration file; `dataset` is what $(dataset) in its paths stands for
/// (empty: none given). Throws stocs::InputError naming the file, the key and the problem:
/// unreadable file, bad YAML, unknown key, wrong type, value out of range, unresolvable path.
NodeConfig loadNodeConfig(const std::filesystem::path& file,
                          const std::filesystem::path& dataset = {});

}  // namespace stocs_ros
