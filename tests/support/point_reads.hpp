// Reading points in the point reader tests: files written byte for byte, the one-line InputError a read
// throws, reads of in-memory text, and a read of "-" with standard input from a file.
#pragma once

#include <gtest/gtest.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cudahull/errors.hpp"
#include "cudahull/point_io.hpp"
#include "temp_dir.hpp"

namespace cudahull {
namespace {

namespace fs = std::filesystem;
const fs::path kData = CUDAHULL_TEST_DATA_DIR;
using testing::TempDir;

void write_file(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << path;
}

// The message of the InputError that `read()` throws ("" and the test failure `failure` if none is thrown).
template <class Read>
std::string input_error(Read read, const std::string& failure) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << failure;
  return "";
}

// The message of the InputError that reading `path` throws.
std::string read_error(const std::string& path) {
  return input_error([&] { read_points(path); }, path + ": no InputError");
}

std::string read_error_text(const std::string& text, PointFormat format) {
  std::istringstream in(text);
  return input_error([&] { read_points(in, format, "mem"); }, "no InputError for:\n" + text);
}

// A gtest name from a file name.
std::string test_name(std::string name) {
  for (char& ch : name) {
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  }
  return name;
}

std::vector<Point3> read_text(const std::string& text, PointFormat format) {
  std::istringstream in(text);
  return read_points(in, format, "mem");
}

// `read_dash()` (a read of "-") with standard input from a file holding `text`, in a child process (so that
// this process's standard input is left alone): the child must exit 0, which it does when `read_dash()`
// returns true.
template <class ReadDash>
void expect_stdin_read(const std::string& text, ReadDash read_dash) {
  TempDir dir;
  write_file(dir / "in.xyz", text);
  const std::string path = (dir / "in.xyz").string();
  const auto child = [&] {
    if (std::freopen(path.c_str(), "r", stdin) == nullptr) std::_Exit(2);
    std::_Exit(read_dash() ? 0 : 1);
  };
  EXPECT_EXIT(child(), ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace cudahull
