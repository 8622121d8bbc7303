// Running the `cudahull` binary from tests: a run that captures stdout, stderr and the exit code
// (shell_run.hpp), and a process started without a shell that a test can signal and time.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "shell_run.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
// The command line under test: the build tree's, or CUDAHULL_CLI's where the tests run away from the build
// tree (the GPU machine, as CUDAHULL_MODELS_DIR points them at the models there).
const std::string kCli = [] {
  const char* env = std::getenv("CUDAHULL_CLI");
  return std::string(env != nullptr && *env != '\0' ? env : CUDAHULL_CLI_PATH);
}();

using cudahull::testing::describe;
using cudahull::testing::shell_quote;
using cudahull::testing::slurp;
using cudahull::testing::TempDir;
using CliRun = cudahull::testing::CommandRun;

// Runs the CLI with `args` (each quoted for the shell), capturing stdout, stderr and the exit code.
CliRun run_cli(const std::vector<std::string>& args) {
  std::vector<std::string> argv{kCli};
  argv.insert(argv.end(), args.begin(), args.end());
  return cudahull::testing::run_command(argv);
}

// A `cudahull` process started with posix_spawn (no shell in between, so its pid is the CLI's own), with
// stdin from /dev/null, stdout and stderr to files in `log_dir`, and SIGINT/SIGTERM/SIGHUP at their
// defaults whatever the test runner inherited; with `ignore_sigint`, SIGINT ignored instead (as a shell
// leaves it for a background job).
struct CliProcess {
  pid_t pid = -1;
  fs::path out_path, err_path;
  std::chrono::steady_clock::time_point started;
};

CliProcess start_cli(const std::vector<std::string>& args, const fs::path& log_dir,
                     bool ignore_sigint = false) {
  static int counter = 0;
  CliProcess p;
  const std::string tag = std::to_string(counter++);
  p.out_path = log_dir / ("stdout." + tag);
  p.err_path = log_dir / ("stderr." + tag);
  std::vector<std::string> argv_strings{kCli};
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_strings)
    argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&files, 1, p.out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&files, 2, p.err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  if (!ignore_sigint) sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  sigaddset(&defaults, SIGHUP);
  // An ignored disposition is inherited through exec: set it here around the spawn.
  struct sigaction ignore {
  }, previous{};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  if (ignore_sigint) ::sigaction(SIGINT, &ignore, &previous);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  p.started = std::chrono::steady_clock::now();
  const int rc = ::posix_spawn(&p.pid, kCli.c_str(), &files, &attr, argv.data(), environ);
  if (ignore_sigint) ::sigaction(SIGINT, &previous, nullptr);
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&files);
  if (rc != 0) {
    ADD_FAILURE() << "posix_spawn " << kCli << ": " << std::strerror(rc);
    p.pid = -1;
  }
  return p;
}

// How a started process ended: its wait status, wall time and peak memory, and what it printed.
struct CliEnd {
  int status = 0;
  double seconds = 0;
  long max_rss_kb = 0;
  std::string out, err;
  bool exited() const { return WIFEXITED(status); }
  int exit_code() const { return WIFEXITED(status) ? WEXITSTATUS(status) : -1; }
  int signal() const { return WIFSIGNALED(status) ? WTERMSIG(status) : 0; }
};

CliEnd wait_cli(const CliProcess& p) {
  CliEnd e;
  if (p.pid < 0) return e;
  struct rusage usage {};
  pid_t r;
  while ((r = ::wait4(p.pid, &e.status, 0, &usage)) < 0 && errno == EINTR) {
  }
  if (r != p.pid) ADD_FAILURE() << "wait4 " << p.pid << ": " << std::strerror(errno);
  e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - p.started).count();
  e.max_rss_kb = usage.ru_maxrss;
  e.out = slurp(p.out_path);
  e.err = slurp(p.err_path);
  return e;
}

std::string describe(const CliEnd& e) {
  const std::string how = e.exited()        ? "exit " + std::to_string(e.exit_code())
                          : e.signal() != 0 ? "killed by signal " + std::to_string(e.signal())
                                            : "status " + std::to_string(e.status);
  return how + " after " + std::to_string(e.seconds) + " s, peak " + std::to_string(e.max_rss_kb) +
         " KiB\n--- stdout:\n" + e.out + "\n--- stderr:\n" + e.err;
}

}  // namespace
