// A program run from tests through the shell: its stdout, stderr and exit code captured.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "temp_dir.hpp"

namespace cudahull::testing {

// `s` as one word for the shell.
inline std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s)
    out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

struct CommandRun {
  int exit_code = -1;  // -1 when the process did not exit normally
  std::string out, err;
};

// Runs `argv` (each word quoted for the shell), in folder `cwd` when given, with stdin from /dev/null,
// capturing stdout, stderr and the exit code.
inline CommandRun run_command(const std::vector<std::string>& argv, const std::string& cwd = "") {
  TempDir dir;
  const std::filesystem::path err_path = dir / "stderr.txt";
  std::string cmd = cwd.empty() ? "" : "cd " + shell_quote(cwd) + " &&";
  for (const auto& a : argv)
    cmd += " " + shell_quote(a);
  cmd += " 2>" + shell_quote(err_path.string()) + " </dev/null";
  CommandRun r;
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

inline std::string describe(const CommandRun& r) {
  return "exit " + std::to_string(r.exit_code) + "\n--- stdout:\n" + r.out + "\n--- stderr:\n" + r.err;
}

}  // namespace cudahull::testing
