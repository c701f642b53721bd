#pragma once
// Runs a program as a child process with its output in a log file, and reports how it ended and
// its peak memory. `stocs bench` runs every method this way: peak memory is then the method's own,
// and a method that crashes ends its run, not the benchmark.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace stocs::tools {

struct ChildOutcome {
  bool exited = false;  ///< ended by exit() (else by a signal, or never started)
  int exit_code = -1;
  int signal = 0;
  bool timed_out = false;  ///< killed for running longer than allowed
  double time_limit = 0;   ///< the limit it exceeded (s), when timed_out
  double peak_rss_mb = 0;  ///< the child's maximum resident set size (getrusage ru_maxrss)
  double seconds = 0;      ///< wall time

  bool ok() const { return exited && exit_code == 0; }
  /// "exit code 2", "killed by signal 11 (Segmentation fault)", "timed out (limit 60 s)", ...
  std::string describe() const;
};

/// Runs `argv` (argv[0] searched in PATH) with standard output and error appended to `log`,
/// calling `waiting` about five times a second until it ends, and killing it (SIGKILL) after
/// `timeout_seconds` when that is positive. Throws InputError when the log cannot be opened or the
/// program cannot be started.
ChildOutcome runChild(const std::vector<std::string>& argv, const std::filesystem::path& log,
                      const std::function<void()>& waiting = {}, double timeout_seconds = 0);

/// The running program's own executable.
std::filesystem::path selfExecutable();

}  // namespace stocs::tools
