// Running the `cudahull` binary from tests: a temporary folder, a run that captures stdout, stderr and the
// exit code, and a process started without a shell that a test can signal and time.
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
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
const std::string kCli = CUDAHULL_CLI_PATH;

class TempDir {
 public:
  TempDir() {
    static int counter = 0;
    path_ = fs::temp_directory_path() /
            ("cudahull_cli_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  fs::path operator/(const std::string& name) const { return path_ / name; }
  std::vector<std::string> files() const { return files_in(path_); }
  // The names in a folder, sorted.
  static std::vector<std::string> files_in(const fs::path& folder) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(folder))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
};

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s)
    out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct CliRun {
  int exit_code = -1;  // -1 when the process did not exit normally
  std::string out, err;
};

// Runs the CLI with `args` (each quoted for the shell), capturing stdout, stderr and the exit code.
CliRun run_cli(const std::vector<std::string>& args) {
  TempDir dir;
  const fs::path err_path = dir / "stderr.txt";
  std::string cmd = shell_quote(kCli);
  for (const auto& a : args)
    cmd += " " + shell_quote(a);
  cmd += " 2>" + shell_quote(err_path.string()) + " </dev/null";
  CliRun r;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (pipe == nullptr) {
    ADD_FAILURE() << "popen failed: " << cmd;
    return r;
  }
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, pipe)) > 0;)
    r.out.append(buf, n);
  const int status = ::pclose(pipe);
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  r.err = slurp(err_path);
  return r;
}

std::string describe(const CliRun& r) {
  return "exit " + std::to_string(r.exit_code) + "\n--- stdout:\n" + r.out + "\n--- stderr:\n" + r.err;
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
