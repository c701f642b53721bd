// The N-input stamp synchronizer: matching within the tolerance for more inputs than
// message_filters supports, newest frame first, and every drop counted by its reason.
#include <gtest/gtest.h>

#include "stocs_ros/stamp_synchronizer.h"

namespace stocs_ros {
namespace {

using Sync = StampSynchronizer<int>;

ros::Time at(double seconds) {
  return ros::Time(1000.0 + seconds);
}

size_t count(const Sync& sync, DropReason reason) {
  return sync.dropCounts()[static_cast<size_t>(reason)];
}

TEST(StampSynchronizer, MatchesTwelveInputsWithinTheTolerance) {
  SyncParams params;
  params.tolerance = 0.01;
  Sync sync(12, params);
  std::vector<DroppedMessage> dropped;
  // Inputs arrive out of order with stamps jittered by up to 8 ms around the reference.
  for (size_t i = 11; i >= 1; --i) {
    const double jitter = (i % 2 ? 1.0 : -1.0) * 0.008 * static_cast<double>(i) / 11.0;
    EXPECT_FALSE(sync.add(i, at(1.0 + jitter), static_cast<int>(100 + i), dropped));
  }
  const auto match = sync.add(0, at(1.0), 100, dropped);
  ASSERT_TRUE(match);
  EXPECT_EQ(match->stamp, at(1.0));
  ASSERT_EQ(match->messages.size(), 12u);
  for (size_t i = 0; i < 12; ++i) EXPECT_EQ(match->messages[i], static_cast<int>(100 + i));
  EXPECT_TRUE(dropped.empty());
}

TEST(StampSynchronizer, StampsBeyondTheToleranceNeverMatch) {
  SyncParams params;
  params.tolerance = 0.01;
  params.queue_size = 3;
  params.max_age = 0;  // only the queue limit applies
  Sync sync(2, params);
  std::vector<DroppedMessage> dropped;
  for (int k = 0; k < 5; ++k) {
    EXPECT_FALSE(sync.add(0, at(k), k, dropped));
    EXPECT_FALSE(sync.add(1, at(k + 0.02), k, dropped));
  }
  // Each queue holds 3; the two oldest of each input went as queue overflow.
  EXPECT_EQ(count(sync, DropReason::kQueueFull), 4u);
  ASSERT_EQ(dropped.size(), 4u);
  EXPECT_EQ(dropped[0].reason, DropReason::kQueueFull);
  EXPECT_EQ(dropped[0].stamp, at(0));
}

TEST(StampSynchronizer, TheNewestCompleteFrameWinsAndOlderOnesAreCounted) {
  Sync sync(2, SyncParams{});
  std::vector<DroppedMessage> dropped;
  EXPECT_FALSE(sync.add(0, at(1.0), 1, dropped));
  EXPECT_FALSE(sync.add(0, at(2.0), 2, dropped));
  EXPECT_FALSE(sync.add(1, at(0.5), 0, dropped));  // matches no cloud
  const auto match = sync.add(1, at(2.003), 20, dropped);
  ASSERT_TRUE(match);
  EXPECT_EQ(match->stamp, at(2.0));
  EXPECT_EQ(match->messages, (std::vector<int>{2, 20}));
  // The cloud at 1.0 and the image at 0.5 can no longer be part of a frame.
  EXPECT_EQ(count(sync, DropReason::kUnmatched), 2u);

  // A late image for the older cloud is dropped as late.
  EXPECT_FALSE(sync.add(1, at(1.0), 10, dropped));
  EXPECT_EQ(count(sync, DropReason::kLate), 1u);
  EXPECT_EQ(dropped.back().input, 1u);
  EXPECT_EQ(describeDropCounts(sync.dropCounts()), "2 unmatched, 1 late");
}

TEST(StampSynchronizer, MessagesBeyondMaxAgeAreDropped) {
  SyncParams params;
  params.max_age = 1.0;
  Sync sync(2, params);
  std::vector<DroppedMessage> dropped;
  EXPECT_FALSE(sync.add(0, at(1.0), 1, dropped));
  EXPECT_FALSE(sync.add(0, at(3.0), 3, dropped));  // the cloud at 1.0 is now too old
  EXPECT_EQ(count(sync, DropReason::kTooOld), 1u);
  EXPECT_FALSE(sync.add(1, at(1.0), 10, dropped));  // too old on arrival
  EXPECT_EQ(count(sync, DropReason::kTooOld), 2u);
  EXPECT_TRUE(sync.add(1, at(3.0), 30, dropped));
}

TEST(StampSynchronizer, StampsNearTheStartOfTheClockWork) {
  SyncParams params;
  params.max_age = 5.0;
  Sync sync(2, params);
  std::vector<DroppedMessage> dropped;
  EXPECT_FALSE(sync.add(0, ros::Time(0.5), 1, dropped));
  EXPECT_TRUE(sync.add(1, ros::Time(0.5), 2, dropped));
}

TEST(StampSynchronizer, ParametersOutOfRangeAreRejected) {
  SyncParams params;
  params.queue_size = 0;
  EXPECT_THROW(params.validate(), std::exception);
  params = SyncParams{};
  params.tolerance = -1;
  EXPECT_THROW(params.validate(), std::exception);
  EXPECT_NO_THROW(SyncParams{}.validate());
}

}  // namespace
}  // namespace stocs_ros
