#pragma once
// The look of generated colour images (`stocs synth`): the light (direction, intensity, colour),
// the table's colour and texture, what lies behind the table, and how closely distractors copy the
// objects' colours. A network trained on the images must not learn one light, one table or
// colour alone. The defaults give the images generated before these options existed, byte for
// byte: one light above and behind the camera, a plain grey table on a dark background.

#include <cstdint>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "stocs/geometry/camera.h"
#include "stocs/util/param_set.h"

namespace stocs {

struct SceneLookParams {
  float light_direction_deg = 0;  ///< light direction drawn within this angle of the default
  float light_intensity = 0;      ///< direct and ambient light each scaled by 1 +- this, drawn
  float light_colour = 0;         ///< each channel of the light scaled by 1 +- this, drawn
  /// A table of a random colour and texture (plain, stripes, tiles or blotches) in front of a
  /// random smooth colour field, instead of the grey table on a dark background.
  bool backgrounds = false;
  float lookalike_share = 0.5f;  ///< share of distractors coloured near a dataset object
  float lookalike_jitter = 20;   ///< a look-alike's channels within +- this many levels

  /// Key, range, unit and meaning of every field (options of `stocs synth`).
  static const ParamSet<SceneLookParams>& schema();
};

/// The look of one image, drawn by drawSceneLook; default-constructed it is the default look.
struct SceneLook {
  /// Direction the light travels, camera frame (from above and behind the camera).
  Eigen::Vector3f light = Eigen::Vector3f(0.3f, 0.6f, 1.0f).normalized();
  float ambient = 0.35f, direct = 0.65f;  ///< gain = ambient + direct x cos(incidence)
  cv::Vec3f light_colour{1, 1, 1};        ///< BGR gains
  /// Empty: the plain grey table. Else the table top's colours (CV_8UC3), its rows along the
  /// table's y and its columns along x, covering the whole table.
  cv::Mat table;
  cv::Mat background;  ///< empty: dark grey; else a CV_8UC3 image the camera's size
};

/// The look of an image from its own random stream of `seed`: the default look where the params
/// ask for no variation.
SceneLook drawSceneLook(const SceneLookParams& params, const CameraIntrinsics& camera,
                        uint64_t seed);

/// Colour (BGR) of a pixel of `colour` lit under `look`, the surface's normal in the camera frame.
cv::Vec3b shade(const cv::Vec3b& colour, const cv::Vec3f& normal, const SceneLook& look);

/// The table's colour at each pixel (CV_8UC3), through a camera at `camera_pose` (table to camera)
/// onto the plane z = 0 of half-width `half_width` metres: the look's texture, or plain `plain`.
cv::Mat tableColours(const SceneLook& look, const cv::Vec3b& plain,
                     const Eigen::Isometry3f& camera_pose, const CameraIntrinsics& camera,
                     float half_width);

}  // namespace stocs
