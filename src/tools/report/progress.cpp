#include "progress.h"

#include <fmt/format.h>

#include <cstdio>

namespace stocs::tools {
namespace {

std::string clock(double seconds) {
  const long s = static_cast<long>(seconds + 0.5);
  return fmt::format("{}:{:02d}", s / 60, s % 60);
}

}  // namespace

Progress::Progress(size_t total, bool interactive) : total_(total), interactive_(interactive) {}

std::string Progress::counter() const {
  return fmt::format("[{}/{}]", done_ + 1, total_);
}

std::string Progress::timing() const {
  const double elapsed = std::chrono::duration<double>(Clock::now() - begin_).count();
  if (done_ == 0) return clock(elapsed) + " elapsed";
  const double left = elapsed / done_ * (total_ - done_);
  return fmt::format("{} elapsed, ~{} left", clock(elapsed), clock(left));
}

void Progress::start(const std::string& label) {
  label_ = label;
  run_start_ = last_line_ = Clock::now();
  update();
}

void Progress::update() {
  const double run = std::chrono::duration<double>(Clock::now() - run_start_).count();
  if (interactive_) {
    const int width = 24;
    const int filled = total_ ? static_cast<int>(width * done_ / total_) : width;
    const std::string current = label_.empty() ? "" : fmt::format("{} ({:.0f} s) ", label_, run);
    fmt::print(stderr, "\r\033[K[{}{}] {}/{} {}{}", std::string(filled, '#'),
               std::string(width - filled, '.'), done_, total_, current, timing());
  } else if (std::chrono::duration<double>(Clock::now() - last_line_).count() >= 60) {
    fmt::print(stderr, "bench {} {}: running for {}\n", counter(), label_, clock(run));
    last_line_ = Clock::now();
  }
  std::fflush(stderr);
}

void Progress::finish(const std::string& outcome) {
  const double run = std::chrono::duration<double>(Clock::now() - run_start_).count();
  const std::string line =
      fmt::format("bench {} {}: {} in {:.1f} s", counter(), label_, outcome, run);
  ++done_;
  if (interactive_) {
    // Failures stay on screen above the bar; successes only move the bar.
    if (outcome != "ok") fmt::print(stderr, "\r\033[K{}\n", line);
    label_.clear();
    update();
  } else {
    fmt::print(stderr, "{} ({})\n", line, timing());
  }
}

void Progress::close() {
  if (interactive_) fmt::print(stderr, "\n");
  std::fflush(stderr);
}

}  // namespace stocs::tools
