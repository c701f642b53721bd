#pragma once
// Progress of a sequence of runs on standard error: a redrawn bar with the current run and the
// time left when standard error is a terminal, else one line per finished run and one a minute
// during a long run, so logs stay readable.

#include <chrono>
#include <cstddef>
#include <string>

namespace stocs::tools {

class Progress {
 public:
  /// `total` runs; `interactive` selects the bar (default: standard error is a terminal).
  explicit Progress(size_t total, bool interactive);

  /// A run starts.
  void start(const std::string& label);
  /// Called while the run goes on.
  void update();
  /// The run ended; `outcome` is shown ("ok", "FAILED: exit code 3, see log ...").
  void finish(const std::string& outcome);
  /// All runs ended: ends the bar's line.
  void close();

 private:
  using Clock = std::chrono::steady_clock;
  std::string counter() const;
  std::string timing() const;

  size_t total_;
  size_t done_ = 0;
  bool interactive_;
  std::string label_;
  Clock::time_point begin_ = Clock::now();
  Clock::time_point run_start_ = begin_;
  Clock::time_point last_line_ = begin_;
};

}  // namespace stocs::tools
