#pragma once
// A test fixture on the three-object scene of test::writeThreeObjectScene: the dataset in a scratch
// folder and the ground truth of its one image.

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <vector>

#include "stocs/io/bop_dataset.h"
#include "test_support.h"

namespace stocs::test {

class ThreeObjectSceneTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = scratchDir("data");
    writeThreeObjectScene(root_);
    dataset_ = std::make_unique<BopDataset>(root_);
    gt_ = dataset_->sceneGroundTruth(0).at(0);
    ASSERT_EQ(gt_.size(), 3u);
  }

  std::filesystem::path root_;
  std::unique_ptr<BopDataset> dataset_;
  std::vector<BopGtInstance> gt_;
};

}  // namespace stocs::test
