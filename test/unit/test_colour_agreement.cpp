// Colour agreement on a rendered box with a red label on one face: the right pose agrees, the box
// turned over (the same depth, the label out of view) does not, whatever the light's colour and
// intensity, only colours in their place count above chance, and a model or frame without colour
// gives no evidence.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <chrono>
#include <opencv2/core.hpp>

#include "stocs/estimation/stages/colour_agreement.h"
#include "stocs/sim/shape_meshes.h"
#include "test_support.h"

namespace stocs {
namespace {

const Eigen::Vector3f kBoxSize(0.1f, 0.06f, 0.04f);

/// The box's colour at model point `q`: a red label in the middle of the +z face, blue elsewhere.
Colour boxColour(const Eigen::Vector3f& q) {
  const bool label =
      q.z() > kBoxSize.z() / 2 - 1e-3f && std::abs(q.x()) < 0.035f && std::abs(q.y()) < 0.02f;
  return label ? Colour(0.8f, 0.15f, 0.1f) : Colour(0.3f, 0.5f, 0.8f);
}

class ColourAgreementTest : public ::testing::Test {
 protected:
  void SetUp() override {
    truth_ = test::viewingPose(0.4f);
    // Turned over about the box's x axis: the same surface in depth, the label facing away.
    turned_ = truth_ * Eigen::AngleAxisf(static_cast<float>(M_PI), Eigen::Vector3f::UnitX());
    model_ = prepareModel(boxMesh(kBoxSize), ModelSamplingParams{});
    for (const Eigen::Vector3f& q : model_.points) model_.colours.push_back(boxColour(q));
    cloud_ =
        cloudFromDepth(test::renderDepth({{boxMesh(kBoxSize), truth_}}, camera_), camera_, 1.0);
  }

  /// The colour image of the box at the true pose under light `light` (per RGB channel).
  cv::Mat image(const Eigen::Vector3f& light) const {
    cv::Mat bgr(cloud_.height, cloud_.width, CV_8UC3, cv::Scalar(40, 40, 40));
    for (int v = 0; v < cloud_.height; ++v) {
      for (int u = 0; u < cloud_.width; ++u) {
        if (!cloud_.isValid(v * cloud_.width + u)) continue;
        const Eigen::Vector3f rgb =
            255 * light.cwiseProduct(boxColour(truth_.inverse() * cloud_.at(u, v)));
        bgr.at<cv::Vec3b>(v, u) =
            cv::Vec3b(cv::saturate_cast<uint8_t>(rgb.z()), cv::saturate_cast<uint8_t>(rgb.y()),
                      cv::saturate_cast<uint8_t>(rgb.x()));
      }
    }
    return bgr;
  }

  ColourAgreement agreement(const Eigen::Isometry3f& pose, const cv::Mat* colour) const {
    return colourAgreement(model_, pose, FreeSpaceCheck(cloud_, camera_, FreeSpaceParams{}),
                           colour);
  }

  CameraIntrinsics camera_ = test::testCamera();
  Eigen::Isometry3f truth_, turned_;
  ObjectModel model_;
  OrganizedCloud cloud_;
};

TEST_F(ColourAgreementTest, TheRightPoseAgreesAndTheBoxTurnedOverDoesNot) {
  const cv::Mat white = image(Eigen::Vector3f::Ones());
  const ColourAgreement right = agreement(truth_, &white), wrong = agreement(turned_, &white);
  ASSERT_TRUE(right.evidence);
  ASSERT_TRUE(wrong.evidence);
  EXPECT_GT(right.samples, 100);
  EXPECT_GT(right.agreement, 0.95f);
  EXPECT_LT(wrong.agreement, right.agreement - 0.2f);
  std::cout << "agreement: right " << right.agreement << ", turned over " << wrong.agreement << " ("
            << right.samples << " samples)\n";
}

TEST_F(ColourAgreementTest, TheLightsColourAndIntensityDoNotChangeTheVerdict) {
  const cv::Mat white = image(Eigen::Vector3f::Ones());
  const cv::Mat warm = image(0.6f * Eigen::Vector3f(1.2f, 1.0f, 0.7f));
  const ColourAgreement right = agreement(truth_, &warm), wrong = agreement(turned_, &warm);
  EXPECT_GT(right.agreement, 0.95f);
  EXPECT_LT(wrong.agreement, right.agreement - 0.2f);
  EXPECT_NEAR(wrong.agreement, agreement(turned_, &white).agreement, 0.05f);
}

// The label in its place agrees well above the same colours paired at random; a box of one colour
// agrees as well whichever way it faces, so its colour is no evidence (colourEvidence 0).
TEST_F(ColourAgreementTest, OnlyColoursInTheirPlaceAreEvidence) {
  const cv::Mat white = image(Eigen::Vector3f::Ones());
  const ColourAgreement right = agreement(truth_, &white);
  EXPECT_GT(colourEvidence(right), 0.2f);
  EXPECT_LT(right.chance, right.agreement - 0.2f);
  ObjectModel blue = model_;
  for (Colour& c : blue.colours) c = Colour(0.3f, 0.5f, 0.8f);
  const ColourAgreement plain =
      colourAgreement(blue, turned_, FreeSpaceCheck(cloud_, camera_, FreeSpaceParams{}), &white);
  ASSERT_TRUE(plain.evidence);
  EXPECT_EQ(colourEvidence(plain), 0.0f) << plain.agreement << " against chance " << plain.chance;
}

TEST_F(ColourAgreementTest, NoColourOrTooFewSamplesGiveNoEvidence) {
  const cv::Mat white = image(Eigen::Vector3f::Ones());
  EXPECT_FALSE(agreement(truth_, nullptr).evidence);
  ObjectModel plain = model_;
  plain.colours.clear();
  EXPECT_FALSE(
      colourAgreement(plain, truth_, FreeSpaceCheck(cloud_, camera_, FreeSpaceParams{}), &white)
          .evidence);
  // Unknown model colour everywhere: nothing to compare.
  ObjectModel unknown = model_;
  for (Colour& c : unknown.colours) c = unknownColour();
  const ColourAgreement none =
      colourAgreement(unknown, truth_, FreeSpaceCheck(cloud_, camera_, FreeSpaceParams{}), &white);
  EXPECT_FALSE(none.evidence);
  EXPECT_EQ(none.samples, 0);
  EXPECT_EQ(none.agreement, 0.0f);
  // Moved 20 cm aside: no sample lands on the measured box.
  Eigen::Isometry3f aside = truth_;
  aside.translation().x() += 0.2f;
  EXPECT_FALSE(agreement(aside, &white).evidence);
}

TEST_F(ColourAgreementTest, TakesWellUnderAMillisecond) {
  const cv::Mat white = image(Eigen::Vector3f::Ones());
  const FreeSpaceCheck check(cloud_, camera_, FreeSpaceParams{});
  constexpr int kRuns = 200;
  const auto start = std::chrono::steady_clock::now();
  float sum = 0;
  for (int k = 0; k < kRuns; ++k) sum += colourAgreement(model_, truth_, check, &white).agreement;
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() /
      kRuns;
  std::cout << "colour agreement: " << ms << " ms per pose, " << model_.size() << " samples\n";
  EXPECT_GT(sum, 0);
  EXPECT_LT(ms, 1.0);
}

}  // namespace
}  // namespace stocs
