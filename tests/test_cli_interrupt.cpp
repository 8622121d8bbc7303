// `cudahull hull` interrupted, run as a separate process: a signal during the write of -o, or at any moment
// of a run, leaves each output complete or absent and no temporary file; an ignored SIGINT stays ignored.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "support/cli_runner.hpp"

namespace {

// ------------------------------------------------------------------------------------------ interrupt

// The contents of each file in a folder, by name.
std::map<std::string, std::string> folder_contents(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const std::string& name : TempDir::files_in(folder))
    files[name] = slurp(folder / name);
  return files;
}

void reset_folder(const fs::path& folder, const std::map<std::string, std::string>& files) {
  for (const std::string& name : TempDir::files_in(folder))
    fs::remove(folder / name);
  for (const auto& [name, bytes] : files)
    std::ofstream(folder / name, std::ios::binary) << bytes;
}

// True once `pid` has stopped or ended, without reaping it (wait_cli does that).
bool stopped_not_ended(pid_t pid) {
  siginfo_t info{};
  while (::waitid(P_PID, static_cast<id_t>(pid), &info, WSTOPPED | WEXITED | WNOWAIT) != 0) {
    if (errno != EINTR) return false;
  }
  return info.si_code == CLD_STOPPED;
}

// A `hull` run on `points` sphere points (every one a hull vertex, so the outputs take megabytes): -o
// (written first) and --vertices-out into `out`.
struct InterruptSetup {
  TempDir dir;
  fs::path out = dir / "out", logs = dir / "logs";
  std::vector<std::string> args;
  explicit InterruptSetup(int points) {
    fs::create_directories(out);
    fs::create_directories(logs);
    const std::string input = (dir / "in.ply").string();
    const CliRun gen = run_cli({"gen", "sphere", std::to_string(points), "--seed", "3", "-o", input});
    EXPECT_EQ(gen.exit_code, 0) << describe(gen);
    args = {"hull",      input, "-o", (out / "out.obj").string(), "--vertices-out", (out / "v.txt").string(),
            "--backend", "cpu", "-q"};
  }
};

// A file's lines, sorted, with face lines reduced to "f": equal for two complete hull files even if the
// engine ordered their faces or vertices differently, and different for a file cut short.
std::vector<std::string> canonical_lines(const std::string& bytes) {
  std::vector<std::string> lines;
  std::istringstream in(bytes);
  for (std::string line; std::getline(in, line);)
    lines.push_back(line.rfind("f ", 0) == 0 ? "f" : line);
  std::sort(lines.begin(), lines.end());
  return lines;
}

// An uninterrupted run: its outputs (-o and --vertices-out) by name, and how long it took.
std::pair<std::map<std::string, std::string>, double> complete_run(const InterruptSetup& s) {
  const CliEnd whole = wait_cli(start_cli(s.args, s.logs));
  EXPECT_EQ(whole.exit_code(), 0) << describe(whole);
  const auto complete = folder_contents(s.out);
  EXPECT_EQ(complete.size(), 2u);
  return {complete, whole.seconds};
}

// Every file in `out` is one of the complete outputs, whole (the same lines), never partial or temporary.
void expect_only_whole_outputs(const fs::path& out, const std::map<std::string, std::string>& complete) {
  for (const auto& [name, bytes] : folder_contents(out)) {
    ASSERT_TRUE(complete.count(name)) << "left behind: " << name;
    EXPECT_TRUE(canonical_lines(bytes) == canonical_lines(complete.at(name)))
        << name << " is partial: " << bytes.size() << " of " << complete.at(name).size() << " bytes";
  }
}

// Starts the run, waits for a new name in the output folder (the temporary file of -o), stops the process
// there (SIGSTOP) and, if out.obj is still as `before`, queues `sig` and lets it go on (SIGCONT), so that
// the signal lands inside the write.  A run that got past out.obj before it could be stopped is killed and
// run again.  Returns how the caught run ended, or nothing after five misses.
std::optional<CliEnd> signal_during_the_write(const InterruptSetup& s,
                                              const std::map<std::string, std::string>& before, int sig,
                                              bool ignore_sigint = false) {
  for (int attempt = 0; attempt < 5; ++attempt) {
    reset_folder(s.out, before);
    const CliProcess p = start_cli(s.args, s.logs, ignore_sigint);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    bool new_name = false;
    while (!new_name && std::chrono::steady_clock::now() < deadline) {
      new_name = TempDir::files_in(s.out).size() > before.size();
      siginfo_t info{};
      if (!new_name && ::waitid(P_PID, static_cast<id_t>(p.pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
          info.si_pid == p.pid) {
        break;  // it ended without writing anything we saw
      }
      if (!new_name) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    bool caught = false;
    if (new_name && ::kill(p.pid, SIGSTOP) == 0 && stopped_not_ended(p.pid)) {
      const auto now = folder_contents(s.out);
      const auto obj = now.find("out.obj");
      const auto was = before.find("out.obj");
      const bool obj_as_before =
          was == before.end() ? obj == now.end() : obj != now.end() && obj->second == was->second;
      caught = obj_as_before && now.size() > before.size();  // a temporary file, out.obj not renamed
      ::kill(p.pid, caught ? sig : SIGKILL);
      ::kill(p.pid, SIGCONT);
    } else {
      ::kill(p.pid, SIGKILL);
    }
    const CliEnd e = wait_cli(p);
    if (caught) return e;
  }
  return std::nullopt;
}

// Ctrl-C, or the terminal closing (SIGHUP), in the middle of writing -o: the process dies by the signal and
// the output folder holds exactly what it held before, byte for byte: no partial out.obj, no
// --vertices-out file, no temporary file; earlier outputs survive.
TEST(CliInterrupt, SignalDuringTheWriteLeavesNothingPartial) {
  InterruptSetup s(50000);
  const std::map<std::string, std::string> earlier{{"out.obj", "# an earlier hull\nv 0 0 0\n"},
                                                   {"v.txt", "0 0 0 0\n"}};
  for (const int sig : {SIGINT, SIGHUP}) {
    for (const auto& before : {std::map<std::string, std::string>{}, earlier}) {
      SCOPED_TRACE(std::string(sig == SIGINT ? "SIGINT, " : "SIGHUP, ") +
                   (before.empty() ? "empty output folder" : "earlier outputs in the folder"));
      const std::optional<CliEnd> e = signal_during_the_write(s, before, sig);
      ASSERT_TRUE(e.has_value()) << "never caught the process while it wrote out.obj";
      EXPECT_EQ(e->signal(), sig) << describe(*e);
      EXPECT_EQ(folder_contents(s.out), before);
    }
  }
}

// A SIGINT that the caller ignores (a background job of a shell) stays ignored while -o is written: the
// run goes on and writes both outputs whole.
TEST(CliInterrupt, IgnoredSigintStaysIgnoredDuringTheWrite) {
  InterruptSetup s(50000);
  const auto [complete, seconds] = complete_run(s);
  ASSERT_EQ(complete.size(), 2u);
  const std::optional<CliEnd> e = signal_during_the_write(s, {}, SIGINT, /*ignore_sigint=*/true);
  ASSERT_TRUE(e.has_value()) << "never caught the process while it wrote out.obj";
  EXPECT_EQ(e->exit_code(), 0) << describe(*e);
  EXPECT_EQ(folder_contents(s.out).size(), complete.size());
  expect_only_whole_outputs(s.out, complete);
}

// SIGINT at a spread of moments, from the start to past the end: whenever it lands, the process either
// dies by it or has finished (exit 0), and each output is either absent or complete (as an uninterrupted
// run writes it), with no temporary file.
TEST(CliInterrupt, SigintAtAnyMomentLeavesCompleteFilesOrNone) {
  InterruptSetup s(20000);
  const auto [complete, seconds] = complete_run(s);
  ASSERT_EQ(complete.size(), 2u);
  const double run_ms = seconds * 1000;
  for (const double fraction : {0.0, 0.5, 0.8, 0.9, 1.0, 1.2}) {
    SCOPED_TRACE("SIGINT at " + std::to_string(fraction) + " of a run");
    reset_folder(s.out, {});
    const CliProcess p = start_cli(s.args, s.logs);
    std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(fraction * run_ms));
    ::kill(p.pid, SIGINT);
    const CliEnd e = wait_cli(p);
    EXPECT_TRUE(e.signal() == SIGINT || e.exit_code() == 0) << describe(e);
    expect_only_whole_outputs(s.out, complete);
  }
}

}  // namespace
