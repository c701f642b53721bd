#pragma once
// One thread that runs estimation jobs, so that subscription and service callbacks never wait for
// an estimation. Two kinds of job:
//  - background jobs (newly synchronized frames): at most one waits, and a newer one replaces it,
//    because a live consumer wants the latest frame rather than a backlog;
//  - requested jobs (service calls): queued in order and run before any waiting background job,
//    with the result or the exception delivered through a future.
// Jobs run one at a time, so whatever `process` touches needs no lock against other jobs.

#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <future>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

namespace stocs_ros {

template <class Job, class Result>
class JobWorker {
 public:
  using Process = std::function<Result(const Job&)>;
  /// Receives what a background job threw (nobody waits for its result).
  using ErrorHandler = std::function<void(std::exception_ptr)>;

  JobWorker(Process process, ErrorHandler on_background_error)
      : process_(std::move(process)), on_background_error_(std::move(on_background_error)) {
    thread_ = std::thread([this] { run(); });
  }

  ~JobWorker() { stop(); }

  /// Lets the running job finish and ends the thread; jobs still waiting are abandoned (their
  /// futures report std::future_errc::broken_promise). Called once, from the owner's thread.
  void stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

  JobWorker(const JobWorker&) = delete;
  JobWorker& operator=(const JobWorker&) = delete;

  /// Queues a background job; returns true when it replaced one that had not started yet.
  bool offer(Job job) {
    bool replaced;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      replaced = background_.has_value();
      background_ = std::move(job);
    }
    wake_.notify_one();
    return replaced;
  }

  /// Queues a requested job ahead of background jobs.
  std::future<Result> request(Job job) {
    std::promise<Result> promise;
    std::future<Result> future = promise.get_future();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      requests_.emplace_back(std::move(job), std::move(promise));
    }
    wake_.notify_one();
    return future;
  }

 private:
  void run() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (true) {
      wake_.wait(lock, [this] { return stopping_ || !requests_.empty() || background_; });
      if (stopping_) return;
      if (!requests_.empty()) {
        auto [job, promise] = std::move(requests_.front());
        requests_.pop_front();
        lock.unlock();
        try {
          promise.set_value(process_(job));
        } catch (...) {
          promise.set_exception(std::current_exception());
        }
      } else {
        Job job = std::move(*background_);
        background_.reset();
        lock.unlock();
        try {
          process_(job);
        } catch (...) {
          on_background_error_(std::current_exception());
        }
      }
      lock.lock();
    }
  }

  Process process_;
  ErrorHandler on_background_error_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::pair<Job, std::promise<Result>>> requests_;
  std::optional<Job> background_;
  bool stopping_ = false;
  std::thread thread_;  // last: starts after every other member is ready
};

}  // namespace stocs_ros
