#pragma once
// The frame-level explanation (issue 45): after every object of a frame has its poses, each
// measured point is explained by at most one accepted pose. Each object is judged alone before it,
// so an absent look-alike fitted on a present object, or a second pose of one box in a bin, is as
// consistent with the depth and its own map as a right pose; here poses that claim the same
// measured surface compete for it, and a pose most of whose confirmed surface another pose
// explains better is rejected ("explained by <object> <k>"); so is a pose on surface that another
// object's map holds more strongly where that object has no pose ("claimed by the map of
// <object>").

#include <string>
#include <vector>

#include "stocs/estimation/stages/free_space_check.h"
#include "stocs/model/object_model.h"
#include "stocs/util/param_set.h"

namespace cv {
class Mat;
}

namespace stocs {

struct InstancePose;

struct FrameExplanationParams {
  /// Choose the published poses of a frame jointly (explainPoses).
  bool enabled = true;
  /// A pose is rejected when more than this share of its confirmed surface is explained by other
  /// accepted poses. A right pose shares only its outline with its neighbours; a pose on another
  /// object's surface shares nearly all of it. One half: the pose's own evidence is then less than
  /// what others explain as well or better.
  float max_explained_share = 0.5f;
  /// An object all of whose poses other objects' poses explain is searched for once more, on its
  /// map without the surface those poses confirm (estimateFrame): its next place, e.g. the box's
  /// own surface when its best pose took a neighbour of its size that another object explains.
  /// Off by default: on maps from depth alone the next place is as often a distractor or an absent
  /// object's (BENCHMARKS.md); on soft maps it changed nothing measured.
  bool search_again = false;

  /// Key, range, unit and meaning of every field (docs/parameters.md).
  static const ParamSet<FrameExplanationParams>& schema();
  /// Throws InputError naming the first value out of range.
  void validate() const;
};

/// One pose of the frame, as the explanation reads and judges it.
struct FramePose {
  std::string object;  ///< the object's name, for the reason
  int instance = 0;    ///< its index among the object's instances, for the reason
  const ObjectModel* model = nullptr;
  const cv::Mat* probability = nullptr;  ///< the object's map (CV_32FC1, the cloud's size)
  InstancePose* pose = nullptr;          ///< judged in place
};

/// An object's map over the frame, as the other objects' poses are read against it.
struct ObjectMap {
  std::string object;
  const cv::Mat* probability = nullptr;  ///< CV_32FC1, the cloud's size
};

/// A pose explainPoses rejected and the pose explaining most of its surface (indices into its
/// `poses`).
struct ExplainedPose {
  size_t pose = 0;
  size_t by = 0;
};

/// Among the accepted poses of `poses`: first, where the maps name objects, a pose more than
/// max_explained_share of whose confirmed pixels (as below) another object's map of `maps` (every
/// object of the frame, posed or not) holds more strongly than its own object's map is rejected,
/// "claimed by the map of <object>": the network gives that surface to another object, which may
/// have no pose there (a box of a bin asked for once). Then each measured pixel a pose confirms (a
/// camera-facing model sample within the free-space margin of the measured depth, splatted over the
/// sample spacing) is explained by another pose when that pose confirms it too and holds it at
/// least as strongly: by its object's map there, or, against another object's pose when the maps do
/// not name objects (`maps_name_objects` false: maps from depth alone mark a region alike for every
/// object of its size), by map x confidence: the pose that fits better holds it. While some
/// accepted pose has more than max_explained_share of its pixels explained by others, the one with
/// the largest such share (the lower confidence on a tie) is rejected, named after the pose
/// explaining most of its pixels, and the shares are counted again. Each pose's
/// `evidence.explained` is then its share (against the poses left; for a rejected one, at its
/// rejection). Does nothing when disabled. Returns the poses rejected for another pose, in that
/// order.
std::vector<ExplainedPose> explainPoses(std::vector<FramePose>& poses,
                                        const FreeSpaceCheck& visibility,
                                        const FrameExplanationParams& params,
                                        bool maps_name_objects = true,
                                        const std::vector<ObjectMap>& maps = {});

/// The pixels (CV_8UC1, 255) that the accepted poses of `poses` for which `counts` is true confirm,
/// splatted as explainPoses claims them: the surface those poses explain.
cv::Mat confirmedArea(const std::vector<FramePose>& poses, const std::vector<bool>& counts,
                      const FreeSpaceCheck& visibility);

}  // namespace stocs
