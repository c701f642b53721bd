#include "child_process.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <thread>

#include "stocs/util/error.h"

extern char** environ;

namespace stocs::tools {

std::string ChildOutcome::describe() const {
  if (timed_out) return fmt::format("timed out (limit {:g} s)", time_limit);
  if (exited) return fmt::format("exit code {}", exit_code);
  if (signal) return fmt::format("killed by signal {} ({})", signal, strsignal(signal));
  return "not started";
}

ChildOutcome runChild(const std::vector<std::string>& argv, const std::filesystem::path& log,
                      const std::function<void()>& waiting, double timeout_seconds) {
  if (log.has_parent_path()) std::filesystem::create_directories(log.parent_path());
  const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) throw InputError(fmt::format("{}: cannot open: {}", log.string(), strerror(errno)));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, fd, STDERR_FILENO);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);

  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(fd);
  if (rc != 0) {
    throw InputError(fmt::format("cannot start {}: {}", argv.at(0), strerror(rc)));
  }
  ChildOutcome out;
  int status = 0;
  rusage usage{};
  for (int polls = 1;; ++polls) {
    const pid_t done = wait4(pid, &status, WNOHANG, &usage);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) {
      throw InputError(fmt::format("waiting for {}: {}", argv.at(0), strerror(errno)));
    }
    // Short polls keep short runs short; `waiting` is called every 0.2 s.
    if (waiting && polls % 10 == 0) waiting();
    if (timeout_seconds > 0 && !out.timed_out &&
        std::chrono::steady_clock::now() - start > std::chrono::duration<double>(timeout_seconds)) {
      kill(pid, SIGKILL);
      out.timed_out = true;
      out.time_limit = timeout_seconds;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.peak_rss_mb = usage.ru_maxrss / 1024.0;  // kilobytes on Linux
  if (WIFEXITED(status)) {
    out.exited = true;
    out.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    out.signal = WTERMSIG(status);
  }
  return out;
}

std::filesystem::path selfExecutable() {
  return std::filesystem::read_symlink("/proc/self/exe");
}

}  // namespace stocs::tools
