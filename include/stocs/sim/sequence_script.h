#pragma once
// What happens in a generated sequence (`stocs synth --sequence`): consecutive frames at a fixed
// rate, the camera on a smooth path (camera_path.h), and object events: one object pushed along
// the table, one lifted and set down elsewhere, one removed and later put back, one hidden for a
// while by an occluder passing in front of it. Each event is a frame range, off when its length is
// 0.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "stocs/sim/scene_layout.h"
#include "stocs/util/param_set.h"
#include "stocs/util/random.h"

namespace stocs {

struct SequenceParams {
  bool enabled = false;                   ///< each scene is a sequence of consecutive frames
  int frames = 300;                       ///< frames per sequence, im_id 0..frames-1
  double rate_hz = 30;                    ///< frames per second
  float translation_speed = 0.15;         ///< greatest speed of the camera, m/s
  float rotation_speed = 0.5;             ///< greatest angular speed of the camera, rad/s
  int push_start = 30, push_frames = 45;  ///< an object slides along the table
  float push_distance = 0.06f;            ///< metres
  int lift_start = 90, lift_frames = 60;  ///< an object rises, moves and is set down
  float lift_height = 0.08f, lift_distance = 0.06f;  ///< metres
  int removal_start = 150, removal_frames = 45;      ///< an object is out of the scene
  int occlusion_start = 210, occlusion_frames = 45;  ///< an occluder passes in front of an object

  /// Key, range, unit and meaning of every field (options of `stocs synth`).
  static const ParamSet<SequenceParams>& schema();
  /// Throws InputError naming the first value out of range or an event that ends after the last
  /// frame.
  void validate() const;
};

enum class SequenceEventKind { kPush, kLift, kRemoval, kOcclusion };

/// "push", "lift", "removal", "occlusion".
std::string sequenceEventName(SequenceEventKind kind);

struct SequenceEvent {
  SequenceEventKind kind = SequenceEventKind::kPush;
  int first_frame = 0, last_frame = 0;  ///< inclusive
  int obj_id = 0;                       ///< the object it happens to
};

/// The objects of one frame, ready to render, with their colours.
struct SequenceFrameObjects {
  std::vector<PlacedObject> objects;  ///< dataset objects, distractors and the occluder
  std::vector<cv::Vec3b> colours;     ///< BGR, one per object
};

/// The camera poses and object poses of every frame of a sequence.
class SequenceScript {
 public:
  /// Places the events on the scene's dataset objects (a different one for each while there are
  /// enough) and draws the camera path, all from `rng`. A push or lift goes in a direction where
  /// the object lands clear of the others, shortened (down to nothing) where none is clear.
  SequenceScript(std::vector<PlacedObject> objects, std::vector<cv::Vec3b> colours,
                 const SequenceParams& params, const SceneLayoutParams& layout, Rng& rng);

  const std::vector<SequenceEvent>& events() const { return events_; }
  /// Table frame to camera at `frame`.
  const Eigen::Isometry3f& camera(int frame) const { return cameras_.at(frame); }
  /// The objects in the scene at `frame` at their poses then: a removed object left out, the
  /// occluder added while it passes.
  SequenceFrameObjects at(int frame) const;

 private:
  /// A push or lift: where the object goes at full progress.
  struct Motion {
    Eigen::Vector3f shift = Eigen::Vector3f::Zero();  ///< along the table, metres
    float height = 0;                                 ///< of a lift, metres
  };

  void addEvent(SequenceEventKind kind, int object, int start, int frames);
  /// The move of `distance` (and `height`, for a lift) that leaves object `object` clear of the
  /// others.
  Motion clearMotion(int object, float distance, float height, Rng& rng) const;
  /// How far object `object` has moved from where it was placed by `frame`.
  Eigen::Vector3f offset(int object, int frame) const;
  bool removedAt(int object, int frame) const;
  /// The occluder of occlusion event `event` at `frame`.
  PlacedObject occluder(int event, int frame) const;

  std::vector<PlacedObject> objects_;
  std::vector<cv::Vec3b> colours_;
  float gap_;
  std::vector<Eigen::Isometry3f> cameras_;
  std::vector<SequenceEvent> events_;
  std::vector<int> event_objects_;  ///< index into objects_ of each event
  std::vector<Motion> motions_;     ///< of each event (zero but for pushes and lifts)
};

}  // namespace stocs
