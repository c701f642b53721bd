#pragma once
// One RGB-D frame as StoCS reads it, and estimateFrame, the entry point that estimates the poses of
// several objects in it: the one the `stocs` tool (with any PoseMethod), the ROS node, the
// tracker's detections and stocs::Estimator all call.

#include <functional>
#include <map>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "stocs/estimation/pipeline.h"
#include "stocs/geometry/camera.h"
#include "stocs/geometry/organized_cloud.h"
#include "stocs/model/model_cache.h"
#include "stocs/segmentation/geometric_segmentation.h"

namespace stocs {

/// A frame: the organized cloud of a depth camera and, per object, the probability map of a
/// segmentation network.
struct Frame {
  OrganizedCloud cloud;  ///< one point per pixel, camera optical frame, metres; NaN: no depth
  /// The cloud's intrinsics (the free-space check projects with them); recovered from the cloud
  /// when missing.
  std::optional<CameraIntrinsics> camera;
  /// Per object name: CV_32FC1 class probabilities in [0, 1], the cloud's size.
  std::map<std::string, cv::Mat> probabilities;
  /// Whether the maps say which object is where (a network's, masks, labels), so that between two
  /// objects' poses on one surface the map decides (explainPoses). False for maps that mark every
  /// region of an object's size alike (setGeometricProbabilities sets it): the better fit decides.
  bool maps_name_objects = true;
  cv::Mat boundary;  ///< optional instance boundary map: CV_8UC1, >= 128 interior
  /// Optional colour image registered with the cloud: CV_8UC3 BGR, the cloud's size, pixel (u, v)
  /// the colour of cloud point (u, v). Empty: no colour.
  cv::Mat colour;

  /// A frame of a depth image (CV_16UC1 or CV_32FC1; `metres_per_unit`: 0.001 for mm) and the
  /// camera that took it, without probability maps yet.
  static Frame fromDepth(const cv::Mat& depth, const CameraIntrinsics& camera,
                         double metres_per_unit);
};

/// Everything the estimation of one object in a frame reads (PoseMethod::estimate). Pointers are
/// never null except `boundary` and `colour`.
struct ObjectInput {
  const OrganizedCloud* cloud = nullptr;
  const CameraIntrinsics* camera = nullptr;  ///< the cloud's intrinsics
  const cv::Mat* probability = nullptr;      ///< CV_32FC1 in [0, 1]
  const cv::Mat* boundary = nullptr;         ///< optional CV_8UC1 instance boundary map
  const cv::Mat* colour = nullptr;           ///< optional CV_8UC3 BGR image (Frame::colour)
  const PreparedModel* model = nullptr;
  /// StoCS parameters; other methods honour the shared ones (seed, threads, time_budget, segment
  /// voxel size and normals).
  const PipelineParams* params = nullptr;
};

/// An object to estimate in a frame: its name (the key of Frame::probabilities) and model.
struct FrameObject {
  std::string name;
  const PreparedModel* model = nullptr;
};

/// One object's outcome in a frame.
struct ObjectResult {
  std::string name;
  PoseEstimate estimate;
  double cpu_seconds = 0;  ///< CPU time of every thread of the process while it ran
};

/// Estimates one object in a frame: another method than StoCS (PoseMethod).
using ObjectEstimator = std::function<PoseEstimate(const ObjectInput&)>;

/// StoCS on one object of a frame (pipeline.h's detectObject on the input's cloud).
PoseEstimate detectObject(const ObjectInput& input);

/// The frame's intrinsics, else those recovered from its cloud.
CameraIntrinsics frameCamera(const Frame& frame);

/// What the estimation of `object` in `frame` reads (pointing into the arguments, which must
/// outlive it). Throws InputError when the frame has no probability map for it, or the map or the
/// colour image does not fit the cloud.
ObjectInput objectInput(const Frame& frame, const CameraIntrinsics& camera,
                        const FrameObject& object, const PipelineParams& params);
/// A temporary camera would not outlive the input that points to it.
ObjectInput objectInput(const Frame& frame, CameraIntrinsics&& camera, const FrameObject& object,
                        const PipelineParams& params) = delete;

/// Depth alone in place of a network: segments the frame's cloud with `segmenter` and sets the
/// probability map of every object of `objects` to the union of the regions that can hold it
/// (objectProbability, by its model's diameter and thinnest width, and by its colours where the
/// frame and the model have colour), and maps_name_objects to false. Returns the segmentation.
/// Throws InputError as GeometricSegmenter::segment does (an empty cloud, one without depth), or
/// for a colour image that does not fit the cloud.
GeometricSegmentation setGeometricProbabilities(Frame& frame,
                                                const std::vector<FrameObject>& objects,
                                                GeometricSegmenter& segmenter);

/// A prepared model's size for the geometric segmentation: its diameter, and the thinnest width of
/// its first samples (an unbiased subsample).
ObjectSize modelSize(const ObjectModel& model);

/// `params` with the confidence model of the frame's maps: ConfidenceParams::depth_alone where they
/// do not name objects (maps from depth alone). estimateFrame and the trackers judge with it.
PipelineParams paramsForMaps(const Frame& frame, const PipelineParams& params);

/// Runs `step`, the work of one object, prefixing an InputError it throws with the object's name
/// ("object 'cat': ...").
void forObject(const std::string& name, const std::function<void()>& step);

/// Every object of `objects` by StoCS (detectObject), one after the other (each uses every
/// thread), in that order. The camera is recovered from the cloud once when the frame has none.
/// Throws InputError naming the object ("object 'cat': ...") when the frame has no probability map
/// for it or the map does not fit the cloud, and any other InputError of the estimation prefixed
/// the same way.
std::vector<ObjectResult> estimateFrame(const Frame& frame, const std::vector<FrameObject>& objects,
                                        const PipelineParams& params);
/// The same loop with another method (`estimate`) in place of StoCS.
std::vector<ObjectResult> estimateFrame(const Frame& frame, const std::vector<FrameObject>& objects,
                                        const PipelineParams& params,
                                        const ObjectEstimator& estimate);

/// The frame-level explanation (explainPoses with PipelineParams::explanation) over every instance
/// of `estimates[i]`, the estimate of `objects[i]` in `frame`: a pose whose confirmed surface other
/// poses explain is rejected in place. estimateFrame calls it; a tracker calls it on the poses it
/// publishes.
void explainFrame(const Frame& frame, const CameraIntrinsics& camera,
                  const std::vector<FrameObject>& objects,
                  const std::vector<PoseEstimate*>& estimates, const PipelineParams& params);

}  // namespace stocs
