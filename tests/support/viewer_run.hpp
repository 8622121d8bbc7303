// cudahull-viewer run from the tests as a user runs it, and its pictures read back: the run's exit code and
// log, PNG screenshots as pixels (blank or not, shades of the faces' state colours, how much two differ), a
// written file's lines, and the frames ffprobe decodes in a recording.  It holds stb_image's implementation:
// include it from one source file of each test executable.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include "renderer.hpp"
#include "shell_run.hpp"
#include "temp_dir.hpp"

namespace cudahull::viewer {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::string kViewer = CUDAHULL_VIEWER_PATH;
const std::string kBunny = std::string(CUDAHULL_ASSETS_DIR) + "/bun_zipper.ply";

// The viewer's arguments and scripts are strings: a TempDir whose names are strings, and that writes files.
class TempDir : public testing::TempDir {
 public:
  std::string operator/(const std::string& name) const { return (path() / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path() / name) << text;
    return *this / name;
  }
};

using ViewerRun = testing::CommandRun;
using testing::describe;
using testing::shell_quote;

// Runs the viewer, in folder `cwd` when given.
ViewerRun run_viewer(const std::vector<std::string>& args, const std::string& cwd = "") {
  std::vector<std::string> argv{kViewer};
  argv.insert(argv.end(), args.begin(), args.end());
  return testing::run_command(argv, cwd);
}

bool has_display() {
  return std::getenv("DISPLAY") != nullptr || std::getenv("WAYLAND_DISPLAY") != nullptr;
}

struct Image {
  int width = 0, height = 0;
  std::vector<std::array<float, 3>> rgb;  // 0..1, top row first
  std::array<float, 3> at(int x, int y) const { return rgb[static_cast<std::size_t>(y) * width + x]; }
};

Image read_png(const std::string& path) {
  Image img;
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &img.width, &img.height, &channels, 3);
  if (data == nullptr) {
    ADD_FAILURE() << "cannot read PNG " << path << ": " << stbi_failure_reason();
    return img;
  }
  img.rgb.resize(static_cast<std::size_t>(img.width) * img.height);
  for (std::size_t i = 0; i < img.rgb.size(); ++i)
    img.rgb[i] = {data[3 * i] / 255.0f, data[3 * i + 1] / 255.0f, data[3 * i + 2] / 255.0f};
  stbi_image_free(data);
  return img;
}

// Variance of the luminance: 0 for a blank picture.
double variance(const Image& img) {
  double sum = 0, sum2 = 0;
  for (const auto& p : img.rgb) {
    const double l = 0.3 * p[0] + 0.59 * p[1] + 0.11 * p[2];
    sum += l;
    sum2 += l * l;
  }
  const double n = static_cast<double>(img.rgb.size());
  return n > 0 ? sum2 / n - (sum / n) * (sum / n) : 0.0;
}

// Is the pixel a shade (k * colour, k in [0.2, 1.05]) of `c`?  The hull shader only ever scales a face's
// base colour (hull.frag.glsl), so an opaque hull's pixels are shades of its states' colours.
bool shade_of(const std::array<float, 3>& p, const glm::vec3& c) {
  const float k = (p[0] * c.r + p[1] * c.g + p[2] * c.b) / glm::dot(c, c);
  if (k < 0.2f || k > 1.05f) return false;
  const float dr = p[0] - k * c.r, dg = p[1] - k * c.g, db = p[2] - k * c.b;
  return std::sqrt(dr * dr + dg * dg + db * db) < 0.05f;
}

// The fraction of pixels in the central box (half the width and height) that satisfy `pred`.
template <typename Pred>
double central_fraction(const Image& img, Pred pred) {
  int hits = 0, total = 0;
  for (int y = img.height / 4; y < img.height * 3 / 4; ++y) {
    for (int x = img.width / 4; x < img.width * 3 / 4; ++x) {
      ++total;
      hits += pred(img.at(x, y)) ? 1 : 0;
    }
  }
  return total ? static_cast<double>(hits) / total : 0.0;
}

bool hull_colored(const std::array<float, 3>& p) {
  for (const glm::vec3& c : kFaceStateColors) {
    if (shade_of(p, c)) return true;
  }
  return false;
}

double differing_fraction(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height) return 1.0;
  int differ = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) {
    const float d = std::abs(a.rgb[i][0] - b.rgb[i][0]) + std::abs(a.rgb[i][1] - b.rgb[i][1]) +
                    std::abs(a.rgb[i][2] - b.rgb[i][2]);
    differ += d > 0.1f ? 1 : 0;
  }
  return static_cast<double>(differ) / static_cast<double>(a.rgb.size());
}

// Only the polyhedron, opaque: what the hull checks look at.
const char* kHullOnly = "hide internal\nhide external\nhide vertices\nset hull-opacity 1\n";

// A file's lines.
std::vector<std::string> lines_of(const std::string& path) {
  return testing::lines_of(testing::slurp(path));
}

bool rgba_near(const std::array<float, 3>& p, std::uint32_t rgba) {
  const float r = (rgba & 0xff) / 255.0f, g = ((rgba >> 8) & 0xff) / 255.0f,
              b = ((rgba >> 16) & 0xff) / 255.0f;
  return std::abs(p[0] - r) + std::abs(p[1] - g) + std::abs(p[2] - b) < 0.12f;
}

// The frames ffprobe decodes in a video file (-1 when it cannot read it).
int decoded_frames(const std::string& path) {
  const std::string cmd =
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=nb_read_frames -of csv=p=0 " +
      shell_quote(path) + " 2>&1";
  std::FILE* pipe = popen(cmd.c_str(), "r");
  if (pipe == nullptr) return -1;
  char line[256] = {};
  const bool read = std::fgets(line, sizeof line, pipe) != nullptr;
  pclose(pipe);
  try {
    return read ? std::stoi(line) : -1;
  } catch (const std::exception&) {
    ADD_FAILURE() << "ffprobe " << path << ": " << line;
    return -1;
  }
}

}  // namespace
}  // namespace cudahull::viewer
