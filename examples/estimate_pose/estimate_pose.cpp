// The poses of the objects of one image of a BOP dataset (as `stocs synth` writes), estimated with
// the C++ interface of stocs_ros outside ROS: stocs::Estimator on a stocs::Frame.
//   estimate_pose DATASET [SCENE IMAGE]
// Prints each object's pose and exits 0 when every object with a probability map was found.
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "stocs/io/bop_dataset.h"
#include "stocs/stocs.h"

int main(int argc, char** argv) {
  if (argc != 2 && argc != 4) {
    std::cerr << "usage: estimate_pose DATASET [SCENE IMAGE]\n";
    return 2;
  }
  const int scene = argc == 4 ? std::atoi(argv[2]) : 0;
  const int image = argc == 4 ? std::atoi(argv[3]) : 0;
  try {
    const stocs::BopDataset dataset(argv[1]);
    const stocs::BopFrameCamera camera = dataset.sceneCameras(scene).at(image);
    const cv::Mat depth = dataset.loadDepth(scene, image);

    stocs::Estimator estimator;  // every parameter at its default (docs/parameters.md)
    stocs::Frame frame = stocs::Frame::fromDepth(depth, camera.intrinsics(depth.cols, depth.rows),
                                                 camera.depth_scale / 1000.0);
    const std::map<int, std::vector<stocs::BopGtInstance>> truth = dataset.sceneGroundTruth(scene);
    for (const stocs::BopGtInstance& g : truth.at(image)) {
      const std::string name = "obj_" + std::to_string(g.obj_id);
      if (estimator.model(name) ||
          !std::filesystem::exists(dataset.probabilityPath(scene, image, g.obj_id))) {
        continue;
      }
      estimator.addObject(name, dataset.modelPath(g.obj_id).string());  // mm, as BOP models
      frame.probabilities[name] = dataset.loadProbability(scene, image, g.obj_id);
    }

    int missed = 0;
    for (const stocs::ObjectResult& r : estimator.estimate(frame)) {
      if (!r.estimate.found()) {
        std::cout << r.name << ": no pose\n";
        ++missed;
        continue;
      }
      const Eigen::Vector3f t = r.estimate.best().pose.translation() * 1000.0f;
      std::cout << r.name << ": t = [" << t.x() << " " << t.y() << " " << t.z() << "] mm, score "
                << r.estimate.best().score << ", " << r.estimate.seconds << " s\n";
    }
    return missed == 0 && !frame.probabilities.empty() ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "estimate_pose: " << e.what() << "\n";
    return 2;
  }
}
