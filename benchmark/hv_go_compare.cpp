// PCL's global hypotheses verification (Aldoma et al. 2012, pcl/recognition/hv/hv_go.h) beside
// StoCS's per-object confidence, on one image of a generated look-alike scene (issue 45: measured
// side by side, not integrated). The hypotheses are the poses of a `stocs estimate` results file
// (every pose of the image, e.g. run with --min-confidence 0 and --targets, so that the absent
// look-alikes' poses are among them); each is the model's surface samples moved by its pose.
// The scene is the image's depth cloud without its dominant plane (the table). Prints, per
// hypothesis, the object, its confidence, whether it is right (ADD-S below 10% of the diameter
// to an instance no higher pose of the object took; a pose of an absent object is wrong) and
// whether GO keeps it, then the counts and GO's time.
//   stocs_hv_go DATASET RESULTS.csv SCENE IMAGE [KEY=VALUE...]   (GoSettings: PCL's tutorial values
//   unless given, e.g. regularizer=1 clutter=0)
// Built only with -DSTOCS_HV_GO=ON (hv_go.h takes long to compile).
#include <fmt/format.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/recognition/hv/hv_go.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_plane.h>
#include <pcl/search/kdtree.h>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <opencv2/core.hpp>
#include <set>

#include "stocs/eval/pose_metrics.h"
#include "stocs/geometry/surface_sampling.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/io/bop_results.h"
#include "stocs/io/mesh_io.h"
#include "stocs/sim/depth_renderer.h"
#include "stocs/util/error.h"
#include "stocs/util/random.h"

namespace stocs {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

/// The image's depth as a cloud in metres, without missing pixels.
Cloud::Ptr depthCloud(const cv::Mat& depth_m, const CameraIntrinsics& k) {
  Cloud::Ptr cloud(new Cloud);
  for (int v = 0; v < depth_m.rows; ++v) {
    for (int u = 0; u < depth_m.cols; ++u) {
      const double z = depth_m.at<float>(v, u);
      if (z <= 0) continue;
      cloud->push_back(pcl::PointXYZ(static_cast<float>((u - k.cx) * z / k.fx),
                                     static_cast<float>((v - k.cy) * z / k.fy),
                                     static_cast<float>(z)));
    }
  }
  return cloud;
}

/// `cloud` without the inliers (1 cm) of its dominant plane, found by RANSAC.
Cloud::Ptr withoutPlane(const Cloud::Ptr& cloud) {
  pcl::SampleConsensusModelPlane<pcl::PointXYZ>::Ptr plane(
      new pcl::SampleConsensusModelPlane<pcl::PointXYZ>(cloud));
  pcl::RandomSampleConsensus<pcl::PointXYZ> ransac(plane, 0.01);
  ransac.computeModel();
  pcl::Indices inliers;
  ransac.getInliers(inliers);
  std::vector<bool> on_plane(cloud->size(), false);
  for (const auto i : inliers) on_plane[static_cast<size_t>(i)] = true;
  Cloud::Ptr rest(new Cloud);
  for (size_t i = 0; i < cloud->size(); ++i) {
    if (!on_plane[i]) rest->push_back((*cloud)[i]);
  }
  return rest;
}

/// One pose to verify, with what is known of it.
struct Hypothesis {
  BopResult pose;
  bool right = false;
};

RigidPose rigid(const Eigen::Matrix3d& R, const Eigen::Vector3d& t_mm) {
  return {R, t_mm};
}

/// Marks each pose right when within ADD-S 10% of the diameter of an instance of its object that no
/// higher-scoring pose took.
void labelHypotheses(std::vector<Hypothesis>& hypotheses, const std::vector<BopGtInstance>& truth,
                     const std::map<int, std::vector<Eigen::Vector3f>>& points_mm,
                     const std::map<int, BopObjectInfo>& info) {
  std::sort(hypotheses.begin(), hypotheses.end(),
            [](const Hypothesis& a, const Hypothesis& b) { return a.pose.score > b.pose.score; });
  std::set<size_t> taken;
  for (Hypothesis& h : hypotheses) {
    const AddsMetric adds(points_mm.at(h.pose.obj_id));
    for (size_t i = 0; i < truth.size() && !h.right; ++i) {
      if (truth[i].obj_id != h.pose.obj_id || taken.count(i)) continue;
      const double error =
          adds.error(rigid(h.pose.R, h.pose.t_mm), rigid(truth[i].R, truth[i].t_mm));
      if (error < 0.1 * info.at(h.pose.obj_id).diameter_mm) {
        h.right = true;
        taken.insert(i);
      }
    }
  }
}

/// The model's surface samples (3000), metres, moved by the pose: all of them, and those the camera
/// sees (PCL 1.13's own occlusion reasoning reads uninitialised depth buffers: ZBuffering fills
/// only a quarter of its map): within 3 mm of the model's own rendered depth at their pixel, and
/// not more than `occlusion` behind the measured depth.
struct ModelClouds {
  Cloud::Ptr complete{new Cloud}, visible{new Cloud};
};

ModelClouds modelClouds(const MeshData& mesh, const BopResult& pose, const cv::Mat& depth_m,
                        const CameraIntrinsics& k, float occlusion) {
  Eigen::Isometry3f to_camera = Eigen::Isometry3f::Identity();
  to_camera.linear() = pose.R.cast<float>();
  to_camera.translation() = (pose.t_mm / 1000.0).cast<float>();
  DepthRenderer self(k);
  self.draw(mesh, to_camera, 1);
  Rng rng(1);
  ModelClouds clouds;
  for (const Eigen::Vector3f& p : sampleMeshSurface(mesh, 3000, rng).points) {
    const Eigen::Vector3f q = to_camera * p;
    clouds.complete->push_back(pcl::PointXYZ(q.x(), q.y(), q.z()));
    const int u = static_cast<int>(std::lround(k.fx * q.x() / q.z() + k.cx));
    const int v = static_cast<int>(std::lround(k.fy * q.y() / q.z() + k.cy));
    if (u < 0 || v < 0 || u >= depth_m.cols || v >= depth_m.rows) continue;
    const float own = self.depth().at<float>(v, u), measured = depth_m.at<float>(v, u);
    if (q.z() > own + 0.003f || (measured > 0 && q.z() > measured + occlusion)) continue;
    clouds.visible->push_back(pcl::PointXYZ(q.x(), q.y(), q.z()));
  }
  return clouds;
}

/// GO's settings: PCL's tutorial values unless given as KEY=VALUE arguments.
struct GoSettings {
  float resolution = 0.005f, occupancy = 0.01f, inlier = 0.005f, occlusion = 0.01f;
  float regularizer = 3.0f, clutter_radius = 0.03f, clutter_regularizer = 5.0f, normals = 0.05f;

  /// Sets the field a KEY=VALUE argument names; throws InputError for an unknown key.
  void set(const std::string& argument) {
    const size_t eq = argument.find('=');
    const std::string key = argument.substr(0, eq);
    const float value = eq == std::string::npos ? 0 : std::stof(argument.substr(eq + 1));
    const std::map<std::string, float*> fields = {{"resolution", &resolution},
                                                  {"occupancy", &occupancy},
                                                  {"inlier", &inlier},
                                                  {"occlusion", &occlusion},
                                                  {"regularizer", &regularizer},
                                                  {"clutter_radius", &clutter_radius},
                                                  {"clutter", &clutter_regularizer},
                                                  {"normals", &normals}};
    if (fields.count(key)) {
      *fields.at(key) = value;
    } else {
      throw InputError(fmt::format("unknown setting '{}'", argument));
    }
  }
};

/// GO's choice among the hypotheses and its wall time, seconds.
std::pair<std::vector<bool>, double> verify(const Cloud::Ptr& scene,
                                            const std::vector<ModelClouds>& models,
                                            const GoSettings& s) {
  const auto start = std::chrono::steady_clock::now();
  pcl::GlobalHypothesesVerification<pcl::PointXYZ, pcl::PointXYZ> go;
  go.setResolution(s.resolution);
  go.setResolutionOccupancyGrid(s.occupancy);
  go.setInlierThreshold(s.inlier);
  go.setOcclusionThreshold(s.occlusion);
  go.setRegularizer(s.regularizer);
  go.setRadiusClutter(s.clutter_radius);
  go.setClutterRegularizer(s.clutter_regularizer);
  go.setDetectClutter(s.clutter_regularizer > 0);
  go.setRadiusNormals(s.normals);
  go.setSceneCloud(scene);
  std::vector<Cloud::ConstPtr> complete, visible;
  for (const ModelClouds& m : models) {
    complete.push_back(m.complete);
    visible.push_back(m.visible);
  }
  go.addCompleteModels(complete);
  go.addModels(visible, false);
  go.verify();
  std::vector<bool> mask;
  go.getMask(mask);
  return {mask, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

/// The share of `model`'s points with a scene point within `radius`.
double inlierShare(pcl::search::KdTree<pcl::PointXYZ>& scene, const Cloud& model, float radius) {
  pcl::Indices index;
  std::vector<float> distance;
  size_t near = 0;
  for (const pcl::PointXYZ& p : model)
    near += scene.radiusSearch(p, radius, index, distance, 1) > 0;
  return model.empty() ? 0.0 : static_cast<double>(near) / model.size();
}

int run(const std::string& root, const std::string& results, int scene, int im,
        const GoSettings& settings) {
  const BopDataset dataset(root);
  const std::map<int, BopObjectInfo> info = dataset.modelsInfo();
  std::map<int, MeshData> meshes;
  std::map<int, std::vector<Eigen::Vector3f>> points_mm;
  std::vector<Hypothesis> hypotheses;
  for (const BopResult& r : readBopResults(results)) {
    if (r.scene_id != scene || r.im_id != im) continue;
    if (!meshes.count(r.obj_id)) {
      meshes[r.obj_id] = loadMesh(dataset.modelPath(r.obj_id).string(), 0.001f);
      for (const Eigen::Vector3f& v : meshes[r.obj_id].vertices)
        points_mm[r.obj_id].push_back(v * 1000);
    }
    hypotheses.push_back({r, false});
  }
  if (hypotheses.empty()) {
    throw InputError(fmt::format("{}: no pose of scene {} image {}", results, scene, im));
  }
  labelHypotheses(hypotheses, dataset.sceneGroundTruth(scene).at(im), points_mm, info);
  const BopFrameCamera camera = dataset.sceneCameras(scene).at(im);
  cv::Mat depth_m;
  dataset.loadDepth(scene, im).convertTo(depth_m, CV_32F, camera.depth_scale / 1000.0);
  const CameraIntrinsics k = camera.intrinsics(depth_m.cols, depth_m.rows);
  std::vector<ModelClouds> models;
  for (const Hypothesis& h : hypotheses) {
    models.push_back(modelClouds(meshes.at(h.pose.obj_id), h.pose, depth_m, k, settings.occlusion));
  }
  const Cloud::Ptr cloud = withoutPlane(depthCloud(depth_m, k));
  const auto [kept, seconds] = verify(cloud, models, settings);
  pcl::search::KdTree<pcl::PointXYZ> tree;
  tree.setInputCloud(cloud);
  int counts[2][2] = {{0, 0}, {0, 0}};  // [right][kept]
  for (size_t i = 0; i < hypotheses.size(); ++i) {
    const Hypothesis& h = hypotheses[i];
    fmt::print(
        "object {:2d} confidence {:.3f} {:5s} GO {}; {} visible samples, {:.0f}% within the inlier "
        "threshold of the scene\n",
        h.pose.obj_id, h.pose.score, h.right ? "right" : "wrong", kept[i] ? "keeps" : "drops",
        models[i].visible->size(), 100.0 * inlierShare(tree, *models[i].visible, settings.inlier));
    ++counts[h.right][kept[i]];
  }
  fmt::print(
      "{} hypotheses, scene {} points without the table: GO keeps {} of {} right and {} of {} "
      "wrong, "
      "in {:.3f} s\n",
      hypotheses.size(), cloud->size(), counts[1][1], counts[1][0] + counts[1][1], counts[0][1],
      counts[0][0] + counts[0][1], seconds);
  return 0;
}

}  // namespace
}  // namespace stocs

int main(int argc, char** argv) {
  if (argc < 5) {
    fmt::print(stderr, "usage: {} DATASET RESULTS.csv SCENE IMAGE [KEY=VALUE...]\n", argv[0]);
    return 2;
  }
  try {
    stocs::GoSettings settings;
    for (int i = 5; i < argc; ++i) settings.set(argv[i]);
    return stocs::run(argv[1], argv[2], std::stoi(argv[3]), std::stoi(argv[4]), settings);
  } catch (const std::exception& e) {
    fmt::print(stderr, "stocs_hv_go: {}\n", e.what());
    return 2;
  }
}
