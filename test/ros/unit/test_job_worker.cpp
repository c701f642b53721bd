// The estimation worker: requested jobs before waiting background jobs, a newer background job
// replacing a waiting one, and errors delivered to the caller or the error handler.
#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "stocs_ros/stocs_node/job_worker.h"

namespace stocs_ros {
namespace {

/// Records the jobs it runs; job 0 blocks until released, so that others queue up behind it.
class Recorder {
 public:
  int run(int job) {
    if (job == 0) released_.wait();
    if (job < 0) throw std::runtime_error("job " + std::to_string(job) + " failed");
    std::lock_guard<std::mutex> lock(mutex_);
    order_.push_back(job);
    return job * 10;
  }
  void release() { release_.set_value(); }
  std::vector<int> order() {
    std::lock_guard<std::mutex> lock(mutex_);
    return order_;
  }

 private:
  std::promise<void> release_;
  std::shared_future<void> released_ = release_.get_future().share();
  std::mutex mutex_;
  std::vector<int> order_;
};

TEST(JobWorker, RequestsRunBeforeTheLatestBackgroundJob) {
  Recorder recorder;
  std::vector<std::string> errors;
  JobWorker<int, int> worker([&](const int& job) { return recorder.run(job); },
                             [&](std::exception_ptr) { errors.push_back("error"); });
  std::future<int> blocker = worker.request(0);
  EXPECT_FALSE(worker.offer(1));
  EXPECT_TRUE(worker.offer(2));  // replaces 1, which never runs
  std::future<int> first = worker.request(3);
  std::future<int> second = worker.request(4);
  recorder.release();
  EXPECT_EQ(blocker.get(), 0);
  EXPECT_EQ(first.get(), 30);
  EXPECT_EQ(second.get(), 40);
  // The waiting background job runs once no request is left; nobody waits for its result.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (recorder.order().size() < 4 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(recorder.order(), (std::vector<int>{0, 3, 4, 2}));
  EXPECT_TRUE(errors.empty());
}

TEST(JobWorker, ErrorsReachTheCallerOrTheHandler) {
  Recorder recorder;
  std::promise<std::string> background_error;
  JobWorker<int, int> worker([&](const int& job) { return recorder.run(job); },
                             [&](std::exception_ptr e) {
                               try {
                                 std::rethrow_exception(e);
                               } catch (const std::exception& x) {
                                 background_error.set_value(x.what());
                               }
                             });
  recorder.release();
  std::future<int> failing = worker.request(-1);
  EXPECT_THROW(failing.get(), std::runtime_error);
  worker.offer(-2);
  EXPECT_EQ(background_error.get_future().get(), "job -2 failed");
  EXPECT_EQ(worker.request(7).get(), 70);  // still working
}

}  // namespace
}  // namespace stocs_ros
