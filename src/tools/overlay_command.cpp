// `stocs overlay`: draws the poses of a BOP results file over one image of the dataset, with the
// ground truth outlined, for a look at what an estimator did.
#include <fmt/format.h>

#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "commands.h"
#include "report/pose_overlay.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_results.h"
#include "stocs/io/mesh_io.h"
#include "stocs/util/error.h"

namespace stocs::tools {
namespace {

struct OverlayOptions {
  std::string dataset;
  std::string results;
  std::string out;
  std::string split = "test";
  int scene = 0;
  int image = 0;
  float unit_scale = 0.001f;
};

Eigen::Isometry3f toMetres(const Eigen::Matrix3d& R, const Eigen::Vector3d& t_mm) {
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.linear() = R.cast<float>();
  pose.translation() = (t_mm / 1000.0).cast<float>();
  return pose;
}

/// The colour image when the dataset has one, else the depth image as grey levels.
cv::Mat background(const BopDataset& dataset, int scene, int image) {
  const std::filesystem::path rgb = dataset.rgbPath(scene, image);
  if (std::filesystem::exists(rgb)) {
    cv::Mat bgr = cv::imread(rgb.string(), cv::IMREAD_COLOR);
    if (bgr.empty()) throw InputError(fmt::format("{}: not a readable image", rgb.string()));
    return bgr;
  }
  cv::Mat depth = dataset.loadDepth(scene, image), grey, bgr;
  cv::normalize(depth, grey, 0, 255, cv::NORM_MINMAX, CV_8U, depth > 0);
  cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

int runOverlay(const OverlayOptions& o) {
  const BopDataset dataset(o.dataset, o.split);
  const std::map<int, BopFrameCamera> cameras = dataset.sceneCameras(o.scene);
  const auto camera = cameras.find(o.image);
  if (camera == cameras.end()) {
    throw InputError(
        fmt::format("dataset {}: scene {} has no image {}", o.dataset, o.scene, o.image));
  }
  const cv::Mat back = background(dataset, o.scene, o.image);
  const CameraIntrinsics k = camera->second.intrinsics(back.cols, back.rows);

  std::map<int, OverlayObject> objects;
  std::map<int, MeshData> models;
  for (const BopResult& r : readBopResults(o.results)) {
    if (r.scene_id != o.scene || r.im_id != o.image) continue;
    if (!models.count(r.obj_id)) {
      models[r.obj_id] = loadMesh(dataset.modelPath(r.obj_id).string(), o.unit_scale);
    }
    objects[r.obj_id].estimates.push_back(toMetres(r.R, r.t_mm));
  }
  if (objects.empty()) {
    throw InputError(
        fmt::format("{}: no result for scene {} image {}", o.results, o.scene, o.image));
  }
  const auto gt = dataset.sceneGroundTruth(o.scene);
  const auto truths = gt.find(o.image);
  int index = 0;
  std::vector<OverlayObject> drawn;
  for (auto& [obj, overlay] : objects) {
    overlay.model = &models.at(obj);
    overlay.colour = objectColour(index++);
    if (truths != gt.end()) {
      for (const BopGtInstance& g : truths->second) {
        if (g.obj_id == obj) overlay.truths.push_back(toMetres(g.R, g.t_mm));
      }
    }
    drawn.push_back(overlay);
  }
  const cv::Mat image = drawPoseOverlay(back, k, drawn);
  if (!cv::imwrite(o.out, image))
    throw InputError(fmt::format("{}: cannot write the image", o.out));
  fmt::print(stderr, "{} object(s) drawn over scene {} image {}: {}\n", drawn.size(), o.scene,
             o.image, o.out);
  return 0;
}

}  // namespace

Command registerOverlay(CLI::App& app) {
  auto o = std::make_shared<OverlayOptions>();
  CLI::App* cmd = app.add_subcommand(
      "overlay", "Draw the poses of a BOP results file over an image, with the truth outlined");
  cmd->add_option("--dataset", o->dataset, "BOP dataset folder")->required();
  cmd->add_option("--results", o->results, "BOP results CSV")->required();
  cmd->add_option("--out", o->out, "PNG file to write")->required();
  cmd->add_option("--split", o->split, "Dataset split folder");
  cmd->add_option("--scene", o->scene, "Scene id");
  cmd->add_option("--image", o->image, "Image id");
  cmd->add_option("--model-scale", o->unit_scale, "Metres per model file unit");
  return {cmd, [o] { return runOverlay(*o); }};
}

}  // namespace stocs::tools
