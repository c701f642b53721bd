// Depth-only segmentation on a rendered tabletop: the table goes, the objects become regions, two
// touching boxes are parted by the crease edges where they meet, and each object's map holds the
// regions of its size. On real YCB-Video frames the desk goes too. Bad input gives InputError.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "stocs/io/bop_dataset.h"
#include "stocs/io/mesh_io.h"
#include "stocs/segmentation/geometric_segmentation.h"
#include "stocs/sim/depth_noise.h"
#include "stocs/sim/depth_renderer.h"
#include "stocs/sim/shape_meshes.h"
#include "test_support.h"

namespace stocs {
namespace {
using test::expectInputError;

constexpr int kTable = 1, kTall = 2, kLow = 3, kCan = 4;

CameraIntrinsics camera() {
  CameraIntrinsics c;
  c.fx = c.fy = 615;
  c.cx = 319.5;
  c.cy = 239.5;
  c.width = 640;
  c.height = 480;
  return c;
}

/// Table frame (z up, top at z = 0) to camera: 0.75 m away, 50 degrees above the table.
Eigen::Isometry3f tableToCamera() {
  const float elevation = 50.0f * static_cast<float>(M_PI) / 180.0f, distance = 0.75f;
  const Eigen::Vector3f centre(0, -distance * std::cos(elevation), distance * std::sin(elevation));
  const Eigen::Vector3f z = -centre.normalized(), x = Eigen::Vector3f::UnitX(), y = z.cross(x);
  Eigen::Matrix3f axes;  // the camera's axes in the table frame
  axes << x, y, z;
  Eigen::Isometry3f camera_in_table = Eigen::Isometry3f::Identity();
  camera_in_table.linear() = axes;
  camera_in_table.translation() = centre;
  return camera_in_table.inverse();
}

/// Draws a mesh centred at `at` in the table frame.
void place(DepthRenderer& renderer, const MeshData& mesh, const Eigen::Vector3f& at, int label) {
  renderer.draw(mesh, tableToCamera() * Eigen::Translation3f(at), label);
}

/// A table, a tall box with a low one against its front (the low box's top meets the tall box's
/// front in a valley, without a depth step) and a can, with a Kinect's depth noise.
struct TableScene {
  cv::Mat depth;   ///< CV_32FC1, metres
  cv::Mat labels;  ///< CV_32SC1, the k constants above
  static const TableScene& get() {
    static const TableScene scene = [] {
      DepthRenderer renderer(camera());
      place(renderer, boxMesh({1.2f, 1.2f, 0.02f}), {0, 0, -0.01f}, kTable);
      place(renderer, boxMesh({0.08f, 0.06f, 0.12f}), {-0.06f, 0.03f, 0.06f}, kTall);
      place(renderer, boxMesh({0.08f, 0.06f, 0.05f}), {-0.06f, -0.03f, 0.025f}, kLow);
      place(renderer, cylinderMesh(0.035f, 0.1f, 32), {0.14f, 0.05f, 0}, kCan);
      TableScene s;
      s.depth = applyDepthNoise(renderer.depth(), renderer.normals(), camera(), {}, 7);
      s.labels = renderer.labels();
      return s;
    }();
    return scene;
  }
};

/// The region covering most of the pixels of `label`, and the share of them it covers.
std::pair<int, double> bestRegion(const GeometricSegmentation& seg, const cv::Mat& labels,
                                  int label) {
  const cv::Mat truth = labels == label;
  const double total = cv::countNonZero(truth);
  std::pair<int, double> best{-1, 0.0};
  for (size_t i = 0; i < seg.regions.size(); ++i) {
    const double share = cv::countNonZero(truth & seg.regions[i].mask) / total;
    if (share > best.second) best = {static_cast<int>(i), share};
  }
  return best;
}

/// Share of a region's pixels that lie on `label`.
double purity(const DepthRegion& region, const cv::Mat& labels, int label) {
  return cv::countNonZero(region.mask & (labels == label)) /
         static_cast<double>(cv::countNonZero(region.mask));
}

TEST(GeometricSegmentation, TheTableGoesAndEachObjectIsARegionOfItsOwn) {
  const TableScene& scene = TableScene::get();
  GeometricSegmenter segmenter;
  const GeometricSegmentation seg = segmenter.segment(scene.depth, camera(), 1.0);
  EXPECT_EQ(seg.planes, 1);
  const cv::Mat table = (scene.labels == kTable) & (scene.depth > 0);
  EXPECT_GT(cv::countNonZero(table & seg.plane_mask), 0.9 * cv::countNonZero(table));
  std::vector<int> found;
  for (int label : {kTall, kLow, kCan}) {
    const auto [region, share] = bestRegion(seg, scene.labels, label);
    ASSERT_GE(region, 0) << "object " << label;
    EXPECT_GT(share, 0.8) << "object " << label;
    EXPECT_GT(purity(seg.regions[region], scene.labels, label), 0.9) << "object " << label;
    found.push_back(region);
  }
  // The touching boxes are two regions.
  EXPECT_NE(found[0], found[1]);
  EXPECT_NE(found[1], found[2]);
  // The tall box shows its top and the front above the low box (12 cm across), the can at most
  // its diagonal (12.2 cm).
  EXPECT_NEAR(seg.regions[found[0]].extent, 0.12f, 0.02f);
  EXPECT_LT(seg.regions[found[2]].extent, 0.13f);
}

// A real sensor's noisy normals break the desk into plane segments each smaller than a supporting
// plane; taken whole, it goes, and each object stands apart from it in a region of its size.
TEST(GeometricSegmentation, EachObjectOfARealDeskFrameLiesInARegionOfItsSize) {
  STOCS_REQUIRE_DATASETS(root);
  const BopDataset ds(root / "ycbv-0000");
  const int scene = ds.sceneIds().front();
  std::map<int, ObjectSize> sizes;
  GeometricSegmenter segmenter;
  for (const auto& [image, truth] : ds.sceneGroundTruth(scene)) {
    const cv::Mat depth = ds.loadDepth(scene, image);
    const BopFrameCamera cam = ds.sceneCameras(scene).at(image);
    const GeometricSegmentation seg =
        segmenter.segment(depth, cam.intrinsics(depth.cols, depth.rows), cam.depth_scale / 1000);
    EXPECT_GE(seg.planes, 1) << "image " << image;
    for (size_t k = 0; k < truth.size(); ++k) {
      const int id = truth[k].obj_id;
      if (!sizes.count(id))
        sizes[id] = ObjectSize::of(loadMesh(ds.modelPath(id).string(), 0.001f).vertices);
      cv::Mat fitting(depth.size(), CV_8UC1, cv::Scalar(0));
      for (const DepthRegion& region : seg.regions) {
        if (regionFits(region, sizes[id], segmenter.params())) fitting |= region.mask;
      }
      const cv::Mat visible =
          cv::imread(ds.maskVisibPath(scene, image, static_cast<int>(k)).string(),
                     cv::IMREAD_GRAYSCALE) > 0;
      EXPECT_GE(cv::countNonZero(visible & fitting), 0.5 * cv::countNonZero(visible))
          << "image " << image << ", object " << id;
    }
  }
}

TEST(GeometricSegmentation, AnObjectsMapHoldsTheRegionsOfItsSize) {
  const TableScene& scene = TableScene::get();
  GeometricSegmenter segmenter;
  const GeometricSegmentation seg = segmenter.segment(scene.depth, camera(), 1.0);
  const GeometricSegmentationParams& params = segmenter.params();
  const cv::Mat tall = scene.labels == kTall;
  // An object whose visible extent (0.95 of its diameter) is the region's 12 cm: confident there
  // (the mean over the box's pixels is below 1 by the blurred border).
  const cv::Mat map = objectProbability(seg, {0.13f, 0.06f}, params);
  ASSERT_EQ(map.type(), CV_32FC1);
  EXPECT_GT(cv::mean(map, tall)[0], 0.8);
  EXPECT_LT(cv::mean(map, scene.labels == kTable)[0], 0.05);
  // The whole box's diagonal (15.6 cm) still fits, with a lower score, above the floor.
  const double whole = cv::mean(objectProbability(seg, {0.156f, 0.06f}, params), tall)[0];
  EXPECT_LT(whole, 0.7);
  EXPECT_GT(whole, 0.9 * params.min_region_score);
  // An object of 3 cm fits in none of these regions, one of 1 m in none either, nor a plate as
  // long as the box but 1 cm thin.
  EXPECT_LT(cv::mean(objectProbability(seg, {0.03f, 0.01f}, params), tall)[0], 0.05);
  EXPECT_LT(cv::mean(objectProbability(seg, {1.0f, 0.5f}, params), tall)[0], 0.05);
  EXPECT_LT(cv::mean(objectProbability(seg, {0.156f, 0.01f}, params), tall)[0], 0.05);
  // One region's own map: confident inside, falling off at its border.
  const auto [region, share] = bestRegion(seg, scene.labels, kTall);
  const cv::Mat own = regionProbability(seg, static_cast<size_t>(region), params);
  const cv::Rect box = seg.regions[region].box;
  EXPECT_NEAR(own.at<float>(box.y + box.height / 2, box.x + box.width / 2), 1.0f, 1e-3);
  EXPECT_LT(cv::mean(own, scene.labels == kCan)[0], 0.01);
}

TEST(GeometricSegmentation, ColourTellsRegionsOfOneSizeApart) {
  // The tall box (12 cm across as seen) is red, the can (at most 12.2 cm) green, shaded: an object
  // of their size and the box's colour gets the box's region first, one of the can's colour the
  // can's; without colour, or with colour_weight 0, the two regions score alike.
  const TableScene& scene = TableScene::get();
  GeometricSegmenter segmenter;
  GeometricSegmentation seg = segmenter.segment(scene.depth, camera(), 1.0);
  cv::Mat bgr(scene.labels.size(), CV_8UC3, cv::Scalar(128, 128, 128));
  bgr.setTo(cv::Scalar(30, 30, 200), scene.labels == kTall);
  bgr.setTo(cv::Scalar(20, 90, 20), scene.labels == kCan);  // darker: shading keeps chromaticity
  addRegionColours(seg, bgr);
  const ChromaticityHistogram red = ChromaticityHistogram::of({Colour(0.8f, 0.1f, 0.1f)});
  const ChromaticityHistogram green = ChromaticityHistogram::of({Colour(0.2f, 0.9f, 0.2f)});
  const cv::Mat tall = scene.labels == kTall, can = scene.labels == kCan;
  const ObjectSize size{0.13f, 0.06f};
  GeometricSegmentationParams params = segmenter.params();
  const cv::Mat as_red = objectProbability(seg, size, params, &red);
  EXPECT_GT(cv::mean(as_red, tall)[0], 2 * cv::mean(as_red, can)[0]);
  const cv::Mat as_green = objectProbability(seg, size, params, &green);
  EXPECT_GT(cv::mean(as_green, can)[0], 2 * cv::mean(as_green, tall)[0]);
  const cv::Mat plain = objectProbability(seg, size, params);
  EXPECT_NEAR(cv::mean(plain, tall)[0], cv::mean(plain, can)[0], 0.1);
  params.colour_weight = 0;
  const cv::Mat ignored = objectProbability(seg, size, params, &red);
  EXPECT_EQ(cv::countNonZero(ignored != plain), 0);
  expectInputError([&] { addRegionColours(seg, cv::Mat(10, 10, CV_8UC3)); }, "does not fit");
}

TEST(Chromaticity, ColoursWithoutTheirBrightness) {
  const ChromaticityHistogram bright = ChromaticityHistogram::of({Colour(0.8f, 0.2f, 0.1f)});
  const ChromaticityHistogram dim = ChromaticityHistogram::of({Colour(0.4f, 0.1f, 0.05f)});
  const ChromaticityHistogram blue = ChromaticityHistogram::of({Colour(0.1f, 0.2f, 0.8f)});
  EXPECT_NEAR(bright.overlap(dim), 1.0f, 1e-4);
  EXPECT_LT(bright.overlap(blue), 0.05f);
  // Too dark or unknown: no evidence, and no overlap with anything.
  const ChromaticityHistogram none =
      ChromaticityHistogram::of({Colour(0.02f, 0.01f, 0.01f), unknownColour()});
  EXPECT_EQ(none.samples(), 0);
  EXPECT_EQ(none.overlap(bright), 0.0f);
  // A full channel is a model's true colour, but a camera's clipped one.
  const Colour full(1.0f, 0.25f, 0.125f);
  EXPECT_NEAR(ChromaticityHistogram::of({full}).overlap(bright), 1.0f, 1e-4);
  cv::Mat bgr(2, 2, CV_8UC3, cv::Scalar(0.125 * 255, 0.25 * 255, 255));
  bgr.at<cv::Vec3b>(0, 0) = cv::Vec3b(25, 50, 200);
  const ChromaticityHistogram seen = ChromaticityHistogram::of(bgr, cv::Mat(2, 2, CV_8UC1, 1));
  EXPECT_EQ(seen.samples(), 1);
  EXPECT_NEAR(seen.overlap(bright), 1.0f, 1e-4);
  // A mesh's colours come from its surface; a mesh without colour has none.
  MeshData mesh = boxMesh({0.1f, 0.1f, 0.1f});
  EXPECT_EQ(ChromaticityHistogram::of(mesh).samples(), 0);
  mesh.colours.assign(mesh.vertices.size(), Rgba(200, 50, 25, 255));
  EXPECT_NEAR(ChromaticityHistogram::of(mesh).overlap(bright), 1.0f, 1e-3);
}

// A cup seen from above: its rim's depth step cuts its inside from its outside, each too small for
// it. The two touch, and together they are the cup's size, so the cup's map holds both.
TEST(GeometricSegmentation, AnObjectCutInTwoByItsOwnEdgeIsOneCandidate) {
  constexpr int kCup = 5;
  const float radius = 0.04f, height = 0.1f, wall = 0.004f;
  DepthRenderer renderer(camera());
  place(renderer, boxMesh({1.2f, 1.2f, 0.02f}), {0, 0, -0.01f}, kTable);
  place(renderer,
        latheMesh({{0, 0},
                   {radius, 0},
                   {radius, height},
                   {radius - wall, height},
                   {radius - wall, 0.01f},
                   {0, 0.01f}},
                  48),
        {0, 0, 0}, kCup);
  const cv::Mat depth = applyDepthNoise(renderer.depth(), renderer.normals(), camera(), {}, 7);
  const cv::Mat cup = renderer.labels() == kCup;
  GeometricSegmenter segmenter;
  const GeometricSegmentation seg = segmenter.segment(depth, camera(), 1.0);
  const auto [outside, outside_share] = bestRegion(seg, renderer.labels(), kCup);
  ASSERT_GE(outside, 0);
  ASSERT_LT(outside_share, 0.8) << "the cup is one region: nothing to join";
  const ObjectSize size{std::hypot(2 * radius, height), 2 * radius};
  EXPECT_GT(cv::mean(objectProbability(seg, size, segmenter.params()), cup)[0], 0.8);
}

TEST(GeometricSegmentation, WithoutTheEdgesTheTouchingBoxesMerge) {
  const TableScene& scene = TableScene::get();
  GeometricSegmentationParams params;
  params.depth_discontinuity = 0.5f;
  params.crease_angle_deg = 180;
  GeometricSegmenter segmenter(params);
  const GeometricSegmentation seg = segmenter.segment(scene.depth, camera(), 1.0);
  EXPECT_EQ(bestRegion(seg, scene.labels, kTall).first, bestRegion(seg, scene.labels, kLow).first);
}

TEST(GeometricSegmentation, AnObjectsSizeIsItsDiameterAndThinnestWidth) {
  // A 30 x 20 x 5 cm box turned off every axis.
  MeshData box = boxMesh({0.3f, 0.2f, 0.05f});
  const Eigen::Matrix3f turn =
      Eigen::AngleAxisf(0.7f, Eigen::Vector3f(1, 2, 3).normalized()).toRotationMatrix();
  for (Eigen::Vector3f& v : box.vertices) v = turn * v;
  const ObjectSize size = ObjectSize::of(box.vertices);
  EXPECT_NEAR(size.diameter, std::sqrt(0.09f + 0.04f + 0.0025f), 1e-4f);
  EXPECT_NEAR(size.min_width, 0.05f, 0.0005f);
}

TEST(GeometricSegmentation, BadInputIsAnInputError) {
  GeometricSegmenter segmenter;
  const cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(0.8));
  expectInputError([&] { segmenter.segment(cv::Mat(), camera(), 1.0); }, "empty");
  expectInputError([&] { segmenter.segment(cv::Mat(480, 640, CV_8UC1), camera(), 1.0); },
                   "expected one channel");
  expectInputError([&] { segmenter.segment(cv::Mat(240, 320, CV_32FC1), camera(), 1.0); },
                   "depth image is 320x240 but the camera is 640x480");
  expectInputError(
      [&] { segmenter.segment(cv::Mat(480, 640, CV_32FC1, cv::Scalar(0)), camera(), 1.0); },
      "no valid measurement");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  expectInputError(
      [&] { segmenter.segment(cv::Mat(480, 640, CV_32FC1, cv::Scalar(nan)), camera(), 1.0); },
      "no valid measurement");
  CameraIntrinsics bad = camera();
  bad.cx = nan;
  expectInputError([&] { segmenter.segment(depth, bad, 1.0); }, "not finite and positive");
  expectInputError([&] { segmenter.segment(depth, camera(), nan); }, "depth scale");
  OrganizedCloud cloud(320, 240);
  expectInputError([&] { segmenter.segment(cloud, camera()); },
                   "depth cloud is 320x240 but the camera is 640x480");
  expectInputError([&] { segmenter.segment(OrganizedCloud(), camera()); }, "empty");

  GeometricSegmentationParams params;
  params.plane_distance = nan;
  expectInputError([&] { GeometricSegmenter{params}; }, "plane_distance");
  params = {};
  params.min_extent_share = 2.0f;
  expectInputError([&] { GeometricSegmenter{params}; }, "min_extent_share");

  const GeometricSegmentation seg = segmenter.segment(depth, camera(), 1.0);
  expectInputError([&] { objectProbability(seg, {nan, 0.0f}, {}); }, "diameter");
  expectInputError([&] { objectProbability(seg, {-0.1f, 0.0f}, {}); }, "diameter");
  expectInputError([&] { objectProbability(seg, {0.1f, nan}, {}); }, "width");
  expectInputError([&] { regionProbability(seg, seg.regions.size(), {}); }, "does not exist");
}

}  // namespace
}  // namespace stocs
