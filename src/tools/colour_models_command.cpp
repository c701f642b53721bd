// `stocs colour-models`: colours a BOP dataset's models from colour frames whose ground-truth
// poses are known, for models without colour of their own (the YCB-Video point models). Each
// model point is projected into each frame at each ground-truth pose of its object; where it is
// visible (facing the camera and within the free-space margin of the measured depth, as the
// free-space check confirms samples) it takes the pixel's colour, averaged over the frames.
// Points never seen get alpha 0 (unknown colour).
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <opencv2/core.hpp>

#include "commands.h"
#include "stocs/estimation/stages/free_space_check.h"
#include "stocs/geometry/normals.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/io/mesh_io.h"
#include "stocs/io/ply_writer.h"
#include "stocs/util/error.h"

namespace stocs::tools {
namespace {
namespace fs = std::filesystem;

struct ColourModelsOptions {
  std::string dataset;
  std::vector<std::string> images;  ///< SCENE/IM
  std::string out;
  std::string split = "test";
  float margin = FreeSpaceParams{}.margin;
};

struct FrameId {
  int scene = 0;
  int im = 0;
};

FrameId parseFrameId(const std::string& spec) {
  FrameId id;
  char slash = 0, rest = 0;
  if (std::sscanf(spec.c_str(), "%d%c%d%c", &id.scene, &slash, &id.im, &rest) != 3 ||
      slash != '/' || id.scene < 0 || id.im < 0) {
    throw InputError(fmt::format("--images: '{}' is not SCENE/IM (e.g. 0/1)", spec));
  }
  return id;
}

/// Unit normals of the model's points, facing out: a mesh's area-weighted face normals at its
/// vertices, a point model's PCA normals oriented by visibility (as prepareModel orients them).
std::vector<Eigen::Vector3f> pointNormals(const MeshData& mesh) {
  if (!mesh.isMesh()) {
    std::vector<Eigen::Vector3f> normals = estimatePcaNormals(mesh.vertices, 16);
    orientNormalsByVisibility(mesh.vertices, normals);
    return normals;
  }
  std::vector<Eigen::Vector3f> normals(mesh.vertices.size(), Eigen::Vector3f::Zero());
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3f& a = mesh.vertices[t[0]];
    const Eigen::Vector3f n = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
    for (int k = 0; k < 3; ++k) normals[t[k]] += n;
  }
  for (Eigen::Vector3f& n : normals) n.normalize();
  return normals;
}

/// A model being coloured: its points as samples for the free-space check's visibility, and the
/// sum and count of the colours seen at each.
struct ModelColouring {
  MeshData mesh;
  ObjectModel points;
  std::vector<Eigen::Vector3d> sum;
  std::vector<int> seen;

  explicit ModelColouring(MeshData m) : mesh(std::move(m)) {
    points.points = mesh.vertices;
    points.normals = pointNormals(mesh);
    sum.assign(mesh.vertices.size(), Eigen::Vector3d::Zero());
    seen.assign(mesh.vertices.size(), 0);
  }

  /// Adds the colours of the points `visibility` confirms at `pose` in `bgr`.
  void observe(const FreeSpaceCheck& visibility, const Eigen::Isometry3f& pose,
               const cv::Mat& bgr) {
    visibility.visit(points, pose, [&](size_t i, int u, int v, SampleView view) {
      if (view != SampleView::kConfirmed) return;
      const cv::Vec3b& c = bgr.at<cv::Vec3b>(v, u);
      sum[i] += Eigen::Vector3d(c[2], c[1], c[0]);
      ++seen[i];
    });
  }

  /// The mesh with the mean colours; alpha 0 where never seen.
  MeshData coloured() const {
    MeshData out = mesh;
    out.colours.assign(mesh.vertices.size(), Rgba::Zero());
    for (size_t i = 0; i < seen.size(); ++i) {
      if (seen[i] == 0) continue;
      const Eigen::Vector3d mean = (sum[i] / seen[i]).array().round();
      out.colours[i] << mean.cast<uint8_t>(), 255;
    }
    return out;
  }
};

Eigen::Isometry3f gtPose(const BopGtInstance& g) {
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.linear() = g.R.cast<float>();
  pose.translation() = (g.t_mm / 1000.0).cast<float>();
  return pose;
}

/// Adds what frame `id` shows of its ground-truth objects to `models` (loaded on first use).
void observeFrame(const BopDataset& dataset, const FrameId& id, const ColourModelsOptions& o,
                  std::map<int, ModelColouring>& models) {
  const auto cameras = dataset.sceneCameras(id.scene);
  const auto gt = dataset.sceneGroundTruth(id.scene);
  if (!cameras.count(id.im) || !gt.count(id.im)) {
    throw InputError(fmt::format("dataset {}: scene {} has no camera or ground truth for image {}",
                                 o.dataset, id.scene, id.im));
  }
  const cv::Mat depth = dataset.loadDepth(id.scene, id.im);
  const cv::Mat bgr = dataset.loadColour(id.scene, id.im, depth.size());
  if (bgr.empty()) {
    throw InputError(fmt::format("{}: no colour image (.png or .jpg)",
                                 dataset.rgbPath(id.scene, id.im).string()));
  }
  const BopFrameCamera& camera = cameras.at(id.im);
  const CameraIntrinsics k = camera.intrinsics(depth.cols, depth.rows);
  const OrganizedCloud cloud = cloudFromDepth(depth, k, camera.depth_scale / 1000.0);
  FreeSpaceParams params;
  params.margin = o.margin;
  const FreeSpaceCheck visibility(cloud, k, params);
  for (const BopGtInstance& g : gt.at(id.im)) {
    auto it = models.find(g.obj_id);
    if (it == models.end()) {
      it = models.emplace(g.obj_id, loadMesh(dataset.modelPath(g.obj_id).string(), 0.001f)).first;
    }
    it->second.observe(visibility, gtPose(g), bgr);
  }
}

int runColourModels(const ColourModelsOptions& o) {
  const BopDataset dataset(o.dataset, o.split);
  std::map<int, ModelColouring> models;
  for (const std::string& spec : o.images) observeFrame(dataset, parseFrameId(spec), o, models);
  const fs::path out = fs::path(o.out) / "models";
  fs::create_directories(out);
  if (fs::equivalent(out, dataset.root() / "models")) {
    throw InputError(fmt::format("--out {}: would overwrite the dataset's own models", o.out));
  }
  for (const fs::directory_entry& e : fs::directory_iterator(dataset.root() / "models")) {
    if (e.is_regular_file()) {
      fs::copy_file(e.path(), out / e.path().filename(), fs::copy_options::overwrite_existing);
    }
  }
  for (const auto& [obj, colouring] : models) {
    const fs::path file = out / dataset.modelPath(obj).filename();
    writePly(file, colouring.coloured(), 1000.0f, 4);  // mm, as BOP models
    const auto seen = static_cast<size_t>(
        std::count_if(colouring.seen.begin(), colouring.seen.end(), [](int n) { return n > 0; }));
    fmt::print("object {}: {} of {} points coloured ({:.1f} %) -> {}\n", obj, seen,
               colouring.seen.size(), 100.0 * seen / colouring.seen.size(), file.string());
  }
  return 0;
}

}  // namespace

Command registerColourModels(CLI::App& app) {
  auto o = std::make_shared<ColourModelsOptions>();
  CLI::App* cmd = app.add_subcommand("colour-models",
                                     "Colour a dataset's models from colour frames at their "
                                     "ground-truth poses; writes DIR/models");
  cmd->add_option("--dataset", o->dataset, "BOP dataset folder")->required();
  cmd->add_option("--images", o->images, "Frames to colour from, SCENE/IM (e.g. 0/1,0/2)")
      ->required()
      ->delimiter(',');
  cmd->add_option("--out", o->out,
                  "Folder to write models/ into (coloured PLYs, other files copied)")
      ->required();
  cmd->add_option("--split", o->split, "Dataset split folder");
  cmd->add_option("--margin", o->margin,
                  "A point within this distance of the measured depth is seen (m)")
      ->check(CLI::Range(0.0001f, 0.1f));
  return {cmd, [o] { return runColourModels(*o); }};
}

}  // namespace stocs::tools
