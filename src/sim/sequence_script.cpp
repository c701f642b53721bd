#include "stocs/sim/sequence_script.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "stocs/sim/camera_path.h"
#include "stocs/sim/shape_meshes.h"
#include "stocs/util/error.h"

namespace stocs {
namespace {

constexpr float kPi = static_cast<float>(M_PI);

/// 0 before the event, 1 after it, easing in and out over its frames.
float progress(const SequenceEvent& event, int frame) {
  const float s = static_cast<float>(frame - event.first_frame + 1) /
                  static_cast<float>(event.last_frame - event.first_frame + 1);
  const float t = std::clamp(s, 0.0f, 1.0f);
  return t * t * (3 - 2 * t);
}

bool during(const SequenceEvent& event, int frame) {
  return frame >= event.first_frame && frame <= event.last_frame;
}

/// A bar across the view, as an arm reaching in: 6 cm wide, 40 cm tall in the image, 4 cm deep.
const MeshData& occluderMesh() {
  static const MeshData bar = boxMesh({0.06f, 0.4f, 0.04f});
  return bar;
}

const cv::Vec3b kOccluderColour(110, 140, 190);

/// Where an event starts and how long it lasts (0 frames: no such event).
struct EventWindow {
  SequenceEventKind kind;
  int start, frames;
};

std::vector<EventWindow> eventWindows(const SequenceParams& p) {
  return {{SequenceEventKind::kPush, p.push_start, p.push_frames},
          {SequenceEventKind::kLift, p.lift_start, p.lift_frames},
          {SequenceEventKind::kRemoval, p.removal_start, p.removal_frames},
          {SequenceEventKind::kOcclusion, p.occlusion_start, p.occlusion_frames}};
}

}  // namespace

std::string sequenceEventName(SequenceEventKind kind) {
  switch (kind) {
    case SequenceEventKind::kPush:
      return "push";
    case SequenceEventKind::kLift:
      return "lift";
    case SequenceEventKind::kRemoval:
      return "removal";
    case SequenceEventKind::kOcclusion:
      return "occlusion";
  }
  return "unknown";
}

const ParamSet<SequenceParams>& SequenceParams::schema() {
  using P = SequenceParams;
  const ParamRange frame = ParamRange::closed(0, 1000000);
  const ParamRange metres = ParamRange::closed(0, 1);
  static const ParamSet<P> schema =
      ParamSet<P>()
          .add(&P::enabled, "enabled",
               "each scene is one sequence of consecutive frames (camera motion, object events, "
               "scene_events.json)")
          .flag("--sequence")
          .add(&P::frames, "frames", "", ParamRange::closed(2, 1000000), "frames per sequence")
          .flag("--frames")
          .add(&P::rate_hz, "rate_hz", "Hz", ParamRange::aboveUpTo(0, 1000), "frames per second")
          .flag("--rate")
          .add(&P::translation_speed, "translation_speed", "m/s", ParamRange::closed(0, 10),
               "greatest speed of the camera (0: a still camera)")
          .flag("--translation-speed")
          .add(&P::rotation_speed, "rotation_speed", "rad/s", ParamRange::closed(0, 20),
               "greatest angular speed of the camera (0: a still camera)")
          .flag("--rotation-speed")
          .add(&P::push_start, "push_start", "", frame, "first frame of the push")
          .flag("--push-start")
          .add(&P::push_frames, "push_frames", "", frame, "frames of the push (0: none)")
          .flag("--push-frames")
          .add(&P::push_distance, "push_distance", "m", metres, "how far the object slides")
          .flag("--push-distance")
          .add(&P::lift_start, "lift_start", "", frame, "first frame of the lift")
          .flag("--lift-start")
          .add(&P::lift_frames, "lift_frames", "", frame, "frames of the lift (0: none)")
          .flag("--lift-frames")
          .add(&P::lift_height, "lift_height", "m", metres, "how high the object is lifted")
          .flag("--lift-height")
          .add(&P::lift_distance, "lift_distance", "m", metres,
               "how far from where it stood the object is set down")
          .flag("--lift-distance")
          .add(&P::removal_start, "removal_start", "", frame,
               "first frame without the removed object")
          .flag("--removal-start")
          .add(&P::removal_frames, "removal_frames", "", frame,
               "frames the object is out of the scene before it is put back (0: none)")
          .flag("--removal-frames")
          .add(&P::occlusion_start, "occlusion_start", "", frame,
               "first frame of the occluder's pass")
          .flag("--occlusion-start")
          .add(&P::occlusion_frames, "occlusion_frames", "", frame,
               "frames of the occluder's pass in front of an object (0: none)")
          .flag("--occlusion-frames");
  return schema;
}

void SequenceParams::validate() const {
  schema().validate(*this, [](const ParamInfo& info) { return "synth: sequence." + info.key; });
  for (const EventWindow& w : eventWindows(*this)) {
    if (w.frames > 0 && w.start + w.frames > frames) {
      throw InputError(fmt::format(
          "synth: the {0} (--{0}-start {1}, --{0}-frames {2}) ends at frame {3}, after the "
          "sequence's last frame {4} (--frames {5})",
          sequenceEventName(w.kind), w.start, w.frames, w.start + w.frames - 1, frames - 1,
          frames));
    }
  }
}

SequenceScript::SequenceScript(std::vector<PlacedObject> objects, std::vector<cv::Vec3b> colours,
                               const SequenceParams& params, const SceneLayoutParams& layout,
                               Rng& rng)
    : objects_(std::move(objects)), colours_(std::move(colours)), gap_(layout.gap) {
  params.validate();
  std::vector<int> candidates;
  for (size_t i = 0; i < objects_.size(); ++i) {
    if (objects_[i].obj_id > 0) candidates.push_back(static_cast<int>(i));
  }
  for (size_t i = candidates.size(); i > 1; --i) {
    std::swap(candidates[i - 1], candidates[uniformIndex(rng, static_cast<uint32_t>(i))]);
  }
  for (const EventWindow& w : eventWindows(params)) {
    if (w.frames == 0 || candidates.empty()) continue;
    const int object = candidates[events_.size() % candidates.size()];
    addEvent(w.kind, object, w.start, w.frames);
    if (w.kind == SequenceEventKind::kPush) {
      motions_.back() = clearMotion(object, params.push_distance, 0, rng);
    } else if (w.kind == SequenceEventKind::kLift) {
      motions_.back() = clearMotion(object, params.lift_distance, params.lift_height, rng);
    }
  }
  cameras_ =
      smoothCameraPath(layout, params.frames,
                       {params.rate_hz, params.translation_speed, params.rotation_speed}, rng);
}

void SequenceScript::addEvent(SequenceEventKind kind, int object, int start, int frames) {
  events_.push_back({kind, start, start + frames - 1, objects_[object].obj_id});
  event_objects_.push_back(object);
  motions_.emplace_back();
}

SequenceScript::Motion SequenceScript::clearMotion(int object, float distance, float height,
                                                   Rng& rng) const {
  constexpr int kDirections = 12;
  const float first = 2 * kPi * uniform01(rng);
  // The longest clear move: the full distance in the first clear direction, else half, ...
  for (float d = distance; d > 0.005f; d /= 2) {
    for (int k = 0; k < kDirections; ++k) {
      const float angle = first + 2 * kPi * static_cast<float>(k) / kDirections;
      const Eigen::Vector3f shift(d * std::cos(angle), d * std::sin(angle), 0);
      // A push sweeps the whole way; a lift only needs a clear landing.
      const int steps = height > 0 ? 1 : std::max(1, static_cast<int>(std::ceil(d / 0.01f)));
      bool clear = true;
      for (int s = 1; s <= steps && clear; ++s) {
        const Eigen::Isometry3f pose =
            Eigen::Translation3f(shift * static_cast<float>(s) / steps) * objects_[object].pose;
        clear = footprintClear(objects_, object, pose, gap_);
      }
      if (clear) return {shift, height};
    }
  }
  return {};
}

Eigen::Vector3f SequenceScript::offset(int object, int frame) const {
  Eigen::Vector3f total = Eigen::Vector3f::Zero();
  for (size_t e = 0; e < events_.size(); ++e) {
    if (event_objects_[e] != object) continue;
    const Motion& m = motions_[e];
    if (m.height <= 0) {
      total += progress(events_[e], frame) * m.shift;
      continue;
    }
    // A lift: up in its first third, across in the second, down in the third.
    const SequenceEvent& ev = events_[e];
    const int third = std::max(1, (ev.last_frame - ev.first_frame + 1) / 3);
    const SequenceEvent up{ev.kind, ev.first_frame, ev.first_frame + third - 1, ev.obj_id};
    const SequenceEvent across{ev.kind, up.last_frame + 1, ev.last_frame - third, ev.obj_id};
    const SequenceEvent down{ev.kind, across.last_frame + 1, ev.last_frame, ev.obj_id};
    total += progress(across, frame) * m.shift;
    total.z() += m.height * (progress(up, frame) - progress(down, frame));
  }
  return total;
}

PlacedObject SequenceScript::occluder(int event, int frame) const {
  const int object = event_objects_[event];
  const Eigen::Vector3f centre = Eigen::Translation3f(offset(object, frame)) *
                                 objects_[object].pose * centreOfMass(objects_[object].mesh);
  const Eigen::Isometry3f camera_in_table = cameras_[frame].inverse();
  // It comes in from the side in the first quarter of the event, stands in front of the object in
  // the middle half and leaves on the other side, 40% of the way from the object to the camera.
  const float t = static_cast<float>(frame - events_[event].first_frame + 1) /
                  static_cast<float>(events_[event].last_frame - events_[event].first_frame + 1);
  const float side = t < 0.25f ? -(1 - t / 0.25f) : t > 0.75f ? (t - 0.75f) / 0.25f : 0.0f;
  constexpr float kSweep = 0.25f;  // metres from the line of sight at the start and the end
  PlacedObject bar{0, occluderMesh(), Eigen::Isometry3f::Identity()};
  bar.pose.linear() = camera_in_table.linear();
  bar.pose.translation() = centre + 0.4f * (camera_in_table.translation() - centre) +
                           kSweep * side * camera_in_table.linear().col(0);
  return bar;
}

bool SequenceScript::removedAt(int object, int frame) const {
  for (size_t e = 0; e < events_.size(); ++e) {
    if (events_[e].kind == SequenceEventKind::kRemoval && event_objects_[e] == object &&
        during(events_[e], frame))
      return true;
  }
  return false;
}

SequenceFrameObjects SequenceScript::at(int frame) const {
  SequenceFrameObjects out;
  for (size_t i = 0; i < objects_.size(); ++i) {
    if (removedAt(static_cast<int>(i), frame)) continue;
    PlacedObject o = objects_[i];
    o.pose = Eigen::Translation3f(offset(static_cast<int>(i), frame)) * o.pose;
    out.objects.push_back(std::move(o));
    out.colours.push_back(colours_[i]);
  }
  for (size_t e = 0; e < events_.size(); ++e) {
    if (events_[e].kind != SequenceEventKind::kOcclusion || !during(events_[e], frame)) continue;
    out.objects.push_back(occluder(static_cast<int>(e), frame));
    out.colours.push_back(kOccluderColour);
  }
  return out;
}

}  // namespace stocs
