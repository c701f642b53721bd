// The scene publisher playing a generated sequence (sequence_playback.test): frames in image id
// order with increasing stamps, each with its own ground truth on TF, a removed object's gt_ frame
// absent exactly while it is out of the scene, and the sequence starting over after the last frame.
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <tf2_msgs/TFMessage.h>

#include <condition_variable>
#include <mutex>

#include "ros_test_support.h"
#include "stocs/io/bop_dataset.h"
#include "stocs/sim/sequence_info.h"

namespace {

std::string g_dataset;
int g_messages = 40;  ///< TF messages to collect: more than one pass of the sequence

TEST(SequencePlayback, FramesComeInOrderWithTheirGroundTruthAndIncreasingStamps) {
  const stocs::BopDataset dataset(g_dataset);
  const std::map<int, std::vector<stocs::BopGtInstance>> gt = dataset.sceneGroundTruth(0);
  const stocs::SequenceInfo info =
      stocs::readSequenceInfo(stocs::sequenceInfoPath(dataset.sceneDir(0)));
  std::mutex mutex;
  std::condition_variable done;
  std::vector<tf2_msgs::TFMessage> received;
  ros::NodeHandle nh;
  ros::Subscriber sub =
      nh.subscribe<tf2_msgs::TFMessage>("/tf", 200, [&](const tf2_msgs::TFMessage::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!m->transforms.empty() && m->transforms[0].child_frame_id.rfind("gt_", 0) == 0)
          received.push_back(*m);
        if (static_cast<int>(received.size()) >= g_messages) done.notify_all();
      });
  std::unique_lock<std::mutex> lock(mutex);
  ASSERT_TRUE(done.wait_for(lock, std::chrono::seconds(60),
                            [&] { return static_cast<int>(received.size()) >= g_messages; }))
      << received.size() << " ground-truth messages";
  sub.shutdown();

  const stocs::SequenceEvent* removal = nullptr;
  for (const stocs::SequenceEvent& e : info.events) {
    if (e.kind == stocs::SequenceEventKind::kRemoval) removal = &e;
  }
  ASSERT_NE(removal, nullptr);
  int previous = -1, restarts = 0, removed_frames = 0;
  for (size_t k = 0; k < received.size(); ++k) {
    const int im = stocs_ros::test::imageOf(received[k], gt);
    ASSERT_GE(im, 0) << "message " << k << " matches no image's ground truth";
    if (k > 0) {
      EXPECT_GT(received[k].transforms[0].header.stamp, received[k - 1].transforms[0].header.stamp);
      // The next frame, or the first one again after the last.
      const bool restart = im == gt.begin()->first && previous == gt.rbegin()->first;
      EXPECT_TRUE(im == previous + 1 || restart) << "image " << im << " after " << previous;
      restarts += restart;
    }
    // imageOf matched every transform to the image's ground truth: while the removed object is
    // out of the scene its gt_ frame is not sent.
    if (im >= removal->first_frame && im <= removal->last_frame) {
      EXPECT_EQ(received[k].transforms.size() + 1, gt.begin()->second.size()) << "image " << im;
      ++removed_frames;
    }
    previous = im;
  }
  EXPECT_GE(restarts, 1);
  EXPECT_GT(removed_frames, 0);
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_sequence_playback");
  ros::NodeHandle pnh("~");
  pnh.getParam("dataset", g_dataset);
  pnh.param("messages", g_messages, g_messages);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
