// The N-input stamp synchronizer: matching within the tolerance for more inputs than
// message_filters supports, newest frame first, and every drop counted by its reason.
#include <gtest/gtest.h>

#include "stocs_ros/common/stamp_synchronizer.h"

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

  // A late image for the older cloud waits (time might have gone back, see below) and is dropped
  // as late once two more frames are matched.
  EXPECT_FALSE(sync.add(1, at(1.0), 10, dropped));
  for (int k = 3; k <= 4; ++k) {
    EXPECT_EQ(count(sync, DropReason::kLate), 0u);
    EXPECT_FALSE(sync.add(0, at(k), k, dropped));
    EXPECT_TRUE(sync.add(1, at(k), 10 * k, dropped));
  }
  EXPECT_EQ(count(sync, DropReason::kLate), 1u);
  EXPECT_EQ(dropped.back().input, 1u);
  EXPECT_EQ(dropped.back().stamp, at(1.0));
  EXPECT_EQ(describeDropCounts(sync.dropCounts()), "2 unmatched, 1 late");
  EXPECT_EQ(sync.timeJumps(), 0u);
}

TEST(StampSynchronizer, TheSameStampsAgainAreMatchedAgainWhicheverInputComesFirst) {
  // A bag of one frame played in a loop: every pass repeats the stamps, in any input order.
  Sync sync(2, SyncParams{});
  std::vector<DroppedMessage> dropped;
  EXPECT_FALSE(sync.add(0, at(5.0), 1, dropped));
  EXPECT_TRUE(sync.add(1, at(5.0), 10, dropped));
  EXPECT_FALSE(sync.add(1, at(5.0), 20, dropped));  // the image first this time
  const auto second = sync.add(0, at(5.0), 2, dropped);
  ASSERT_TRUE(second);
  EXPECT_EQ(second->messages, (std::vector<int>{2, 20}));
  EXPECT_FALSE(sync.add(0, at(5.0), 3, dropped));  // the cloud first
  const auto third = sync.add(1, at(5.0), 30, dropped);
  ASSERT_TRUE(third);
  EXPECT_EQ(third->messages, (std::vector<int>{3, 30}));
  EXPECT_EQ(sync.timeJumps(), 2u);
  EXPECT_TRUE(dropped.empty());
}

TEST(StampSynchronizer, TimeGoingBackStartsAgainAndDropsWhatWaitedOnTheOldTimeline) {
  // A bag of frames 1..4 in a loop with max_age 1 s: the second pass starts 3 s back.
  SyncParams params;
  params.max_age = 1.0;
  Sync sync(2, params);
  std::vector<DroppedMessage> dropped;
  for (int k = 1; k <= 3; ++k) {
    EXPECT_FALSE(sync.add(0, at(k), k, dropped));
    EXPECT_TRUE(sync.add(1, at(k), 10 * k, dropped));
  }
  EXPECT_FALSE(sync.add(0, at(4), 4, dropped));  // its image never comes
  EXPECT_FALSE(sync.add(1, at(1), 10, dropped));
  ASSERT_TRUE(dropped.empty());
  const auto match = sync.add(0, at(1), 1, dropped);
  ASSERT_TRUE(match) << "the first frame of the second pass";
  EXPECT_EQ(match->messages, (std::vector<int>{1, 10}));
  EXPECT_EQ(sync.timeJumps(), 1u);
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_EQ(dropped[0].reason, DropReason::kTimeJump);
  EXPECT_EQ(dropped[0].stamp, at(4));
  EXPECT_EQ(describeDropCounts(sync.dropCounts()), "1 time jump");
  // The second pass goes on as the first did.
  EXPECT_FALSE(sync.add(0, at(2), 2, dropped));
  EXPECT_TRUE(sync.add(1, at(2), 20, dropped));
  EXPECT_EQ(dropped.size(), 1u);
}

TEST(StampSynchronizer, TheOldTimelinesLastFrameMayCompleteAfterTheNewTimelineBegan) {
  // A bag of frames 1 and 2 in a loop; the second pass's image comes before the first pass's last
  // cloud, a larger message, has arrived.
  Sync sync(2, SyncParams{});
  std::vector<DroppedMessage> dropped;
  EXPECT_FALSE(sync.add(0, at(1), 1, dropped));
  EXPECT_TRUE(sync.add(1, at(1), 10, dropped));
  EXPECT_FALSE(sync.add(1, at(2), 20, dropped));
  EXPECT_FALSE(sync.add(1, at(1), 11, dropped));  // the second pass begins
  EXPECT_TRUE(sync.add(0, at(2), 2, dropped));    // the first pass ends
  const auto match = sync.add(0, at(1), 3, dropped);
  ASSERT_TRUE(match) << "the second pass's first frame";
  EXPECT_EQ(match->messages, (std::vector<int>{3, 11}));
  EXPECT_TRUE(dropped.empty());
}

TEST(StampSynchronizer, ARestartedDriverDropsTheOldTimelinesStragglers) {
  // A simulator restarted: its clock starts again near zero.
  Sync sync(2, SyncParams{});
  std::vector<DroppedMessage> dropped;
  EXPECT_FALSE(sync.add(0, at(100), 1, dropped));
  EXPECT_TRUE(sync.add(1, at(100), 10, dropped));
  EXPECT_FALSE(sync.add(1, at(99.5), 11, dropped));  // a late image of the old timeline
  EXPECT_FALSE(sync.add(0, ros::Time(0.5), 2, dropped));
  EXPECT_EQ(sync.timeJumps(), 1u);
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_EQ(dropped[0].stamp, at(99.5));
  EXPECT_EQ(dropped[0].reason, DropReason::kTimeJump);
  EXPECT_TRUE(sync.add(1, ros::Time(0.5), 20, dropped));
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
