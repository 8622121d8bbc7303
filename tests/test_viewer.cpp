// cudahull-viewer end to end, as a user runs it: headless (EGL; Mesa's llvmpipe in CI) and windowed (GLFW
// under Xvfb), screenshots read back and checked pixel by pixel: not blank, the hull visible in the colours
// of its faces' states, the picture changing between steps and with a layer hidden; script errors name the
// line.  Plus the parts that need no GL: camera JSON, script parsing, numbered paths.  Label: gl.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include "camera.hpp"
#include "cudahull/exact_hull.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/point_io.hpp"
#include "cudahull/point_writer.hpp"
#include "overlay.hpp"
#include "png.hpp"
#include "renderer.hpp"
#include "script.hpp"
#include "support/shell_run.hpp"
#include "support/temp_dir.hpp"
#include "ui_layout.hpp"

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

TEST(ViewerHeadless, BunnyHullIsVisibleInItsStateColours) {
  TempDir dir;
  const std::string script =
      dir.write("hull.txt", std::string(kHullOnly) + "run\nscreenshot " + (dir / "end.png") +
                                "\nrewind 1\nscreenshot " + (dir / "tetra.png") + "\n");
  const ViewerRun r =
      run_viewer({kBunny, "--headless", "--width", "320", "--height", "240", "--script", script});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("CPU upload"));  // the log says which upload path is active

  const Image end = read_png(dir / "end.png");
  ASSERT_EQ(end.width, 320);
  ASSERT_EQ(end.height, 240);
  EXPECT_GT(variance(end), 1e-3);
  EXPECT_GT(central_fraction(end, hull_colored), 0.4);
  EXPECT_TRUE(hull_colored(end.at(160, 120)));

  // Position 1 is the tetrahedron of section 3.1: every face is new, in the "refined" colour.
  const Image tetra = read_png(dir / "tetra.png");
  const glm::vec3 refined = kFaceStateColors[static_cast<int>(FaceState::kRefined)];
  EXPECT_GT(central_fraction(tetra, [&](const auto& p) { return shade_of(p, refined); }), 0.3);
  EXPECT_GT(differing_fraction(end, tetra), 0.05);
}

TEST(ViewerHeadless, PngSequenceChangesBetweenSteps) {
  TempDir dir;
  const ViewerRun r = run_viewer({"--gen", "ball", "20000", "--seed", "3", "--headless", "--width", "256",
                                  "--height", "192", "--steps", "5", "--screenshot", dir / "step_%02d.png"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  for (int k = 0; k <= 5; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "step_%02d.png", k);
    EXPECT_TRUE(fs::exists(dir / name)) << name;
  }
  EXPECT_FALSE(fs::exists(dir / "step_06.png"));
  const Image points = read_png(dir / "step_00.png"), one = read_png(dir / "step_01.png"),
              five = read_png(dir / "step_05.png");
  EXPECT_GT(variance(points), 1e-4);  // the bare point cloud is drawn
  EXPECT_GT(variance(one), 1e-3);
  EXPECT_GT(differing_fraction(one, five), 0.05);
  // No temporary file left behind by the atomic writes.
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(fs::path(dir / "")))
    ++files;
  EXPECT_EQ(files, 6);
}

TEST(ViewerHeadless, HidingTheHullAndMovingTheCameraChangeThePicture) {
  TempDir dir;
  const std::string script =
      dir.write("layers.txt", "step 5\nscreenshot " + (dir / "shown.png") +
                                  "\nhide hull\nhide wireframe\nscreenshot " + (dir / "hidden.png") +
                                  "\nshow hull\nshow wireframe\ncamera {\"yaw\": 120, \"pitch\": 10}\n" +
                                  "screenshot " + (dir / "turned.png") + "\n");
  const ViewerRun r =
      run_viewer({kBunny, "--headless", "--width", "256", "--height", "192", "--script", script});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const Image shown = read_png(dir / "shown.png"), hidden = read_png(dir / "hidden.png"),
              turned = read_png(dir / "turned.png");
  EXPECT_GT(differing_fraction(shown, hidden), 0.05);
  EXPECT_GT(differing_fraction(shown, turned), 0.05);
  // With the hull hidden, no pixel near the centre is a hull colour any more.
  EXPECT_LT(central_fraction(hidden, hull_colored), 0.02);
}

bool background(const std::array<float, 3>& p) {
  const glm::vec3 b = RenderSettings{}.background;
  return std::abs(p[0] - b.r) + std::abs(p[1] - b.g) + std::abs(p[2] - b.b) < 0.03f;
}

// Large clouds are drawn as compute splats (shaders/points_splat.comp.glsl); forced here on a small one,
// they must cover where GL points are drawn, in the same state colours, and sit at the right depth.
TEST(ViewerHeadless, SplatsDrawTheCloudGlPointsDraw) {
  TempDir dir;
  const std::string script = dir.write(
      "splats.txt", "step 3\nhide hull\nhide wireframe\nhide vertices\nset point-mode points\nscreenshot " +
                        (dir / "points.png") + "\nset point-mode splats\nscreenshot " + (dir / "splats.png") +
                        "\nhide external\nshow hull\nset hull-opacity 1\nscreenshot " + (dir / "hull.png") +
                        "\n");
  const ViewerRun r = run_viewer({"--gen", "ball", "20000", "--seed", "3", "--headless", "--width", "256",
                                  "--height", "192", "--script", script});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const Image points = read_png(dir / "points.png"), splats = read_png(dir / "splats.png"),
              hull = read_png(dir / "hull.png");
  ASSERT_EQ(points.rgb.size(), splats.rgb.size());
  std::size_t drawn = 0, covered = 0, splat_pixels = 0;
  for (std::size_t i = 0; i < points.rgb.size(); ++i) {
    splat_pixels += background(splats.rgb[i]) ? 0 : 1;
    if (background(points.rgb[i])) continue;
    ++drawn;
    covered += background(splats.rgb[i]) ? 0 : 1;
  }
  ASSERT_GT(drawn, 1000u);
  EXPECT_GT(static_cast<double>(covered) / drawn, 0.9);  // squares cover the round points
  EXPECT_LT(splat_pixels, 3 * drawn);
  auto internal = [](const auto& p) { return shade_of(p, kInternalColor); };
  auto external = [](const auto& p) { return shade_of(p, kExternalColor); };
  EXPECT_GT(central_fraction(splats, internal), 0.01);
  EXPECT_GT(central_fraction(splats, external), 0.01);
  // An opaque hull hides the internal points behind its faces: the splats wrote their depth (at depth 0
  // they would cover it).
  EXPECT_GT(central_fraction(hull, hull_colored), 0.3);
}

// Issue 6, Fig. 2: selecting a face draws its three separating planes, highlights its cell's points and
// marks its extreme point; the normals layer draws every edge's normal.  Each changes the picture, and
// hiding them gives the plain picture back.
TEST(ViewerHeadless, SelectedFaceCellAndEdgeNormalsChangeThePicture) {
  TempDir dir;
  const std::string script =
      dir.write("cells.txt",
                "step 2\nhide hull\nscreenshot " + (dir / "plain.png") + "\nselect-face 0\nscreenshot " +
                    (dir / "cell.png") + "\nhide cells\nscreenshot " + (dir / "hidden.png") +
                    "\nshow normals\nscreenshot " + (dir / "normals.png") +
                    "\nselect-face 999999\nshow cells\n" + "screenshot " + (dir / "out_of_range.png") + "\n");
  const ViewerRun r = run_viewer({"--gen", "ball", "3000", "--seed", "5", "--headless", "--width", "256",
                                  "--height", "192", "--script", script});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const Image plain = read_png(dir / "plain.png"), cell = read_png(dir / "cell.png"),
              hidden = read_png(dir / "hidden.png"), normals = read_png(dir / "normals.png"),
              out_of_range = read_png(dir / "out_of_range.png");
  EXPECT_GT(differing_fraction(plain, cell), 0.01);
  // The cell's external points turn to the selection colour.
  auto selected = [](const auto& p) { return shade_of(p, kSelectedColor); };
  EXPECT_GT(central_fraction(cell, selected), central_fraction(plain, selected) + 0.001);
  EXPECT_LT(differing_fraction(plain, hidden), 0.001);
  EXPECT_GT(differing_fraction(hidden, normals), 0.003);
  EXPECT_LT(differing_fraction(normals, out_of_range), 0.001);  // an unknown face id draws no cell
}

// A file's lines.
std::vector<std::string> lines_of(const std::string& path) {
  return testing::lines_of(testing::slurp(path));
}

bool rgba_near(const std::array<float, 3>& p, std::uint32_t rgba) {
  const float r = (rgba & 0xff) / 255.0f, g = ((rgba >> 8) & 0xff) / 255.0f,
              b = ((rgba >> 16) & 0xff) / 255.0f;
  return std::abs(p[0] - r) + std::abs(p[1] - g) + std::abs(p[2] - b) < 0.12f;
}

// Issue 17: `set legend on` draws the colour key into the picture (swatches in the palette's colours, in
// the bottom left corner) and `off` gives the same picture back; `show labels` writes the vertex ids (in
// the vertices' yellow) and the face ids (light blue) in the font.
TEST(ViewerHeadless, LegendAndLabelsAppearAndGoAway) {
  TempDir dir;
  const std::string script =
      dir.write("legend.txt", "step 3\nhide internal\nhide external\nscreenshot " + (dir / "plain.png") +
                                  "\nset legend on\nscreenshot " + (dir / "legend.png") +
                                  "\nset legend off\nscreenshot " + (dir / "off.png") +
                                  "\nshow labels\nscreenshot " + (dir / "labels.png") + "\n");
  const ViewerRun r = run_viewer({"--gen", "ball", "12", "--seed", "12", "--headless", "--width", "480",
                                  "--height", "360", "--script", script});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("text: font "));
  const Image plain = read_png(dir / "plain.png"), legend = read_png(dir / "legend.png"),
              off = read_png(dir / "off.png"), labels = read_png(dir / "labels.png");
  EXPECT_GT(differing_fraction(plain, legend), 0.01);
  EXPECT_EQ(differing_fraction(plain, off), 0.0);
  // Each swatch of the faces' key is a square of its exact colour in the bottom left quarter.
  auto count_in_corner = [](const Image& img, const glm::vec3& c) {
    std::size_t n = 0;
    for (int y = img.height / 2; y < img.height; ++y) {
      for (int x = 0; x < img.width / 2; ++x) {
        const auto p = img.at(x, y);
        n += std::abs(p[0] - c.r) + std::abs(p[1] - c.g) + std::abs(p[2] - c.b) < 0.03f ? 1 : 0;
      }
    }
    return n;
  };
  for (const glm::vec3& c : kFaceStateColors)
    EXPECT_GE(count_in_corner(legend, c), count_in_corner(plain, c) + 60) << c.r << " " << c.g << " " << c.b;
  auto count = [](const Image& img, const glm::vec3& c) {
    std::size_t n = 0;
    for (const auto& p : img.rgb)
      n += rgba_near(p, pack_rgba(c.r, c.g, c.b, 1.0f)) ? 1 : 0;
    return n;
  };
  EXPECT_LT(count(plain, kFaceIdColor), 5u);
  EXPECT_GT(count(labels, kFaceIdColor), 40u);
  EXPECT_GT(count(labels, kVertexColor), count(plain, kVertexColor) + 40);
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

// Issue 17: recordings through ffmpeg have one frame per step (an .mp4), one per sub-step (`substep all`,
// a .gif), and --record records a whole headless run; a path that is neither .mp4 nor .gif is a usage error.
TEST(ViewerHeadless, RecordingsHaveOneFramePerStepOrSubStep) {
  TempDir dir;
  const std::string script =
      dir.write("record.txt", "record start " + (dir / "steps.mp4") +
                                  "\nstep 4\nrecord stop\nnext-removal\nrecord start " +
                                  (dir / "phases.gif") + "\nsubstep all\nrecord stop\n");
  const ViewerRun r = run_viewer({"--gen", "ball", "3000", "--seed", "5", "--headless", "--width", "161",
                                  "--height", "121", "--script", script});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("steps.mp4 (4 frames)"));
  EXPECT_EQ(decoded_frames(dir / "steps.mp4"), 4);
  const std::size_t played = r.err.find("played sub-steps 0 to ");
  ASSERT_NE(played, std::string::npos) << r.err;
  const int phases = std::stoi(r.err.substr(played + 22)) + 1;
  EXPECT_GE(phases, 4);
  EXPECT_EQ(decoded_frames(dir / "phases.gif"), phases);
  EXPECT_FALSE(fs::exists(dir / "phases.gif.partial"));

  // The bunny's whole run: one frame per iteration.
  const ViewerRun b =
      run_viewer({kBunny, "--headless", "--width", "96", "--height", "72", "--record", dir / "bunny.mp4",
                  "--script", dir.write("run.txt", "run\nexport-trace " + (dir / "t.jsonl") + "\n")});
  ASSERT_EQ(b.exit_code, 0) << describe(b);
  EXPECT_EQ(decoded_frames(dir / "bunny.mp4"), static_cast<int>(lines_of(dir / "t.jsonl").size()));

  const ViewerRun bad =
      run_viewer({kBunny, "--headless", "--script", dir.write("bad.txt", "record start a.avi\n")});
  EXPECT_EQ(bad.exit_code, 2) << describe(bad);
  EXPECT_THAT(bad.err, HasSubstr("bad.txt:1: 'record start' needs a .mp4 or .gif path"));
}

// Issue 17, picking: a scripted hover names the point under the mouse (its id, that it is external, its
// face and its signed distance to that face's plane, positive: outside) and a click there explains that
// same point's route, ending where the backend put it; over a face, the hover names the face and a click
// selects it and draws its cell.
TEST(ViewerHeadless, HoverAndClickNameWhatIsUnderTheMouse) {
  TempDir dir;
  const std::string script = dir.write(
      "pick.txt",
      "step 2\nhide hull\nhide internal\nhide vertices\nhover 160 120\nclick 160 120\n"
      "show hull\nhide external\nscreenshot " +
          (dir / "before.png") + "\nhover 160 120\nclick 160 120\nscreenshot " + (dir / "after.png") + "\n");
  const ViewerRun r = run_viewer({"--gen", "ball", "3000", "--seed", "5", "--headless", "--width", "320",
                                  "--height", "240", "--script", script});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const std::string point_hover = "hover 160 120: point ";
  const std::size_t at = r.err.find(point_hover);
  ASSERT_NE(at, std::string::npos) << r.err;
  const std::string point = r.err.substr(at + point_hover.size(),
                                         r.err.find(':', at + point_hover.size()) - at - point_hover.size());
  EXPECT_THAT(r.err, HasSubstr(point_hover + point + ": external, face "));
  EXPECT_THAT(r.err, HasSubstr(", signed distance +"));
  const std::size_t explained = r.err.find("click 160 120: explain point " + point + ":");
  ASSERT_NE(explained, std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the backend agrees (face ", explained), std::string::npos) << r.err;

  const std::string face_hover = "hover 160 120: face ";
  const std::size_t f = r.err.find(face_hover);
  ASSERT_NE(f, std::string::npos) << r.err;
  const std::string face =
      r.err.substr(f + face_hover.size(), r.err.find(':', f + face_hover.size()) - f - face_hover.size());
  EXPECT_THAT(r.err, HasSubstr("click 160 120: selected face " + face + " "));
  EXPECT_GT(differing_fraction(read_png(dir / "before.png"), read_png(dir / "after.png")), 0.01);
}

// Issue 17, the input layer: the model's own surface (a PLY's face element; an OBJ's faces through
// the face reader) drawn grey under the points; a generated cloud has none, and the layer changes nothing.
TEST(ViewerHeadless, InputLayerDrawsTheModelsOwnSurface) {
  TempDir dir;
  auto grey_fraction = [](const Image& img) {
    return central_fraction(img, [](const auto& p) {
      return std::abs(p[0] - p[1]) < 0.02f && std::abs(p[1] - p[2]) < 0.02f && p[0] > 0.3f;
    });
  };
  const std::string script =
      dir.write("input.txt",
                "step 2\nhide hull\nhide wireframe\nhide internal\n"
                "hide external\nhide vertices\nscreenshot " +
                    (dir / "bare.png") + "\nshow input\nscreenshot " + (dir / "input.png") + "\n");
  for (const std::string model : {"bun_zipper.ply", "teapot.obj"}) {
    const ViewerRun r = run_viewer({std::string(CUDAHULL_ASSETS_DIR) + "/" + model, "--headless", "--width",
                                    "240", "--height", "180", "--script", script});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_LT(grey_fraction(read_png(dir / "bare.png")), 0.001) << model;
    EXPECT_GT(grey_fraction(read_png(dir / "input.png")), 0.2) << model;
  }
  const ViewerRun g = run_viewer(
      {"--gen", "ball", "500", "--headless", "--width", "240", "--height", "180", "--script", script});
  ASSERT_EQ(g.exit_code, 0) << describe(g);
  EXPECT_EQ(differing_fraction(read_png(dir / "bare.png"), read_png(dir / "input.png")), 0.0);
}

// Issue 17, no moire on the bunny at the defaults: the scan's points are drawn as large as their spacing
// on the screen, so the bare cloud is a closed surface, with (next to) no background pixel enclosed by drawn
// ones.  At the old fixed default of 3 pixels, at 960x720, the same measure finds the gaps between the scan
// lines that made the moire.
TEST(ViewerHeadless, BunnyScanDrawsAsAClosedSurfaceAtTheDefaults) {
  TempDir dir;
  auto enclosed_gaps = [](const Image& img) {  // background pixels with drawn ones 2 pixels away all round
    std::size_t drawn = 0, gaps = 0;
    for (int y = 2; y + 2 < img.height; ++y) {
      for (int x = 2; x + 2 < img.width; ++x) {
        if (!background(img.at(x, y))) {
          ++drawn;
        } else if (!background(img.at(x - 2, y)) && !background(img.at(x + 2, y)) &&
                   !background(img.at(x, y - 2)) && !background(img.at(x, y + 2))) {
          ++gaps;
        }
      }
    }
    return drawn > 0 ? static_cast<double>(gaps) / drawn : 1.0;
  };
  const std::string script =
      dir.write("bare.txt", "screenshot " + (dir / "auto.png") + "\nset point-size 3\nscreenshot " +
                                (dir / "three.png") + "\n");
  for (const auto& [width, height] : {std::pair{480, 360}, std::pair{960, 720}}) {
    const ViewerRun r = run_viewer({kBunny, "--headless", "--width", std::to_string(width), "--height",
                                    std::to_string(height), "--script", script});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_LT(enclosed_gaps(read_png(dir / "auto.png")), 0.005) << width << "x" << height;
  }
  EXPECT_GT(enclosed_gaps(read_png(dir / "three.png")), 0.02);  // 960x720, the last
}

// Issue 6, Figs. 3-5 and 7: next-rejected stops at a step that rejected a swap; the swaps layer draws that
// step's swaps (green new edges) and the rejected foldover (orange old edge, magenta beneath-triangle); the
// refinement layer changes the picture; the exported decision table is the trace's decision array for the
// step, entry by entry; the exported mesh has the step's faces.
TEST(ViewerHeadless, SwapsRefinementAndExportsMatchTheTrace) {
  TempDir dir;
  const std::string script =
      dir.write("debug.txt",
                "next-rejected\nhide internal\nhide external\nhide hull\nhide wireframe\nhide vertices\n"
                "screenshot " +
                    (dir / "plain.png") + "\nshow swaps\nscreenshot " + (dir / "swaps.png") +
                    "\nhide swaps\nshow refinement\nscreenshot " + (dir / "refinement.png") +
                    "\nexport-trace " + (dir / "trace.jsonl") + "\nexport-decisions " +
                    (dir / "decisions.csv") + "\nexport-mesh " + (dir / "mesh.obj") + "\n");
  const ViewerRun r = run_viewer({"--gen", "ball", "3000", "--seed", "5", "--headless", "--width", "320",
                                  "--height", "240", "--script", script});
  ASSERT_EQ(r.exit_code, 0) << describe(r);

  const std::vector<std::string> trace = lines_of(dir / "trace.jsonl");
  ASSERT_FALSE(trace.empty());
  const nlohmann::json step = nlohmann::json::parse(trace.back());
  EXPECT_GT(step["swaps_rejected"].get<int>(), 0) << "next-rejected stopped at a step without a rejection";
  for (std::size_t k = 0; k + 1 < trace.size(); ++k)
    EXPECT_EQ(nlohmann::json::parse(trace[k])["swaps_rejected"].get<int>(), 0)
        << "an earlier rejection at " << k;

  const std::vector<std::string> csv = lines_of(dir / "decisions.csv");
  const nlohmann::json& decisions = step["decisions"];
  ASSERT_EQ(csv.size(), decisions.size() + 1);  // header
  for (std::size_t k = 0; k < decisions.size(); ++k) {
    const nlohmann::json& d = decisions[k];
    std::istringstream row(csv[k + 1]);
    std::vector<std::string> cells;
    for (std::string cell; std::getline(row, cell, ',');)
      cells.push_back(cell);
    ASSERT_GE(cells.size(), 7u) << csv[k + 1];
    EXPECT_EQ(cells[0], std::to_string(k));
    EXPECT_EQ(cells[1], d["kind"].get<std::string>());
    if (d["kind"] == "swap") {
      EXPECT_DOUBLE_EQ(std::stod(cells[2]), d["plane"][0].get<double>()) << k;
      EXPECT_DOUBLE_EQ(std::stod(cells[5]), d["plane"][3].get<double>()) << k;
    }
  }

  std::size_t faces = 0;
  for (const std::string& line : lines_of(dir / "mesh.obj"))
    faces += line.rfind("f ", 0) == 0 ? 1 : 0;
  EXPECT_EQ(faces, step["faces_after"].get<std::size_t>());

  const Image plain = read_png(dir / "plain.png"), swaps = read_png(dir / "swaps.png"),
              refinement = read_png(dir / "refinement.png");
  auto count = [](const Image& img, std::uint32_t rgba) {
    std::size_t n = 0;
    for (const auto& p : img.rgb)
      n += rgba_near(p, rgba) ? 1 : 0;
    return n;
  };
  EXPECT_GT(count(swaps, kRegularSwapRgba), 20u);
  EXPECT_GT(count(swaps, kFoldoverRgba) + count(swaps, kBeneathRgba), 5u);
  // The sequence numbers beside the swaps (seven-segment digits, near white).
  EXPECT_GT(count(swaps, pack_rgba(0.9f, 1.0f, 0.9f, 1.0f)), 10u);
  EXPECT_EQ(count(plain, kRegularSwapRgba) + count(plain, kBeneathRgba), 0u);
  EXPECT_GT(differing_fraction(plain, refinement), 0.01);
}

// Issue 6, item 7: every demo in demos/ renders headless, and each really contains its case (from the
// trace it exports): a regular swap (Fig. 3), a rejected foldover with its vertex beneath (Fig. 5), a
// removal after complementary swaps (Fig. 4), and the bunny's whole run (Fig. 10).
TEST(ViewerHeadless, DemosRenderAndShowTheirCases) {
  TempDir dir;
  fs::create_directory_symlink(CUDAHULL_ASSETS_DIR, dir / "assets");
  fs::create_directories(dir / "out/demos");  // as scripts/demos does: a screenshot never makes folders
  std::string last_log;
  auto run_demo = [&](const std::string& name) {
    const std::string path = std::string(CUDAHULL_DEMOS_DIR) + "/" + name + ".txt";
    std::ifstream in(path);
    std::string first;
    std::getline(in, first);
    const std::string prefix = "# cudahull-viewer ";
    EXPECT_EQ(first.rfind(prefix, 0), 0u) << path << " does not start with its input";
    std::vector<std::string> args;
    std::istringstream words(first.substr(prefix.size()));
    for (std::string w; words >> w;)
      args.push_back(w);
    for (std::string a : {"--headless", "--width", "320", "--height", "240", "--script"})
      args.push_back(a);
    args.push_back(path);
    const ViewerRun r = run_viewer(args, dir / "");
    EXPECT_EQ(r.exit_code, 0) << name << ": " << describe(r);
    last_log = r.err;
    const std::vector<std::string> trace =
        lines_of(dir / ("out/demos/" + name.substr(0, name.find('_')) + ".jsonl"));
    return trace.empty() ? nlohmann::json() : nlohmann::json::parse(trace.back());
  };
  auto has_swap = [](const nlohmann::json& step, const std::string& kind) {
    for (const auto& w : step["swaps"])
      if (w["kind"] == kind && (kind != "rejected_foldover" || w.contains("beneath_vertex"))) return true;
    return false;
  };

  const nlohmann::json swap = run_demo("swap_fig3");
  EXPECT_TRUE(has_swap(swap, "regular"));
  EXPECT_GT(differing_fraction(read_png(dir / "out/demos/swap_1_refinement.png"),
                               read_png(dir / "out/demos/swap_3_swaps.png")),
            0.01);

  EXPECT_TRUE(has_swap(run_demo("foldover_fig5"), "rejected_foldover"));
  // `frame rejected` names the case and says whether a later edit of the step resolved it.
  EXPECT_THAT(last_log, HasSubstr("lies beneath"));
  EXPECT_THAT(last_log, ::testing::AnyOf(HasSubstr("resolved later"), HasSubstr("not resolved")));
  EXPECT_GT(variance(read_png(dir / "out/demos/foldover.png")), 1e-3);

  const nlohmann::json removal = run_demo("removal_fig4");
  EXPECT_TRUE(has_swap(removal, "complementary"));
  bool removed = false;
  for (const auto& m : removal["removals"])
    removed = removed || !m["rejected"].get<bool>();
  EXPECT_TRUE(removed);
  EXPECT_GT(variance(read_png(dir / "out/demos/removal.png")), 1e-3);

  const nlohmann::json bunny = run_demo("bunny_fig10");
  EXPECT_EQ(bunny["external_after"].get<std::size_t>(), 0u) << "the bunny demo runs to the end";
  for (const char* png : {"bunny_00.png", "bunny_01.png", "bunny_05.png"})
    EXPECT_GT(variance(read_png(dir / ("out/demos/" + std::string(png)))), 1e-4) << png;
  // Issue 17: one animation per demo beside its pictures: the bunny's iterations, the others' sub-steps.
  EXPECT_EQ(decoded_frames(dir / "out/demos/bunny.gif"), bunny["iteration"].get<int>() + 1);
  for (const char* gif : {"swap.gif", "foldover.gif", "removal.gif"})
    EXPECT_GE(decoded_frames(dir / ("out/demos/" + std::string(gif))), 4) << gif;
}

// Issue 6, item 4: "explain point" retraces a point's route through the step's refinement[] and decision[]
// (Fig. 7) to a face or "internal"; for every point it must end where the backend put the point.
TEST(ViewerHeadless, ExplainPointEndsWhereTheBackendPutThePoint) {
  TempDir dir;
  std::string script = "step 3\n";
  for (int i = 0; i < 60; ++i)
    script += "explain-point " + std::to_string(i) + "\n";
  script += "rewind 1\nexplain-point 7\nscreenshot " + (dir / "x.png") + "\n";
  const ViewerRun r = run_viewer({"--gen", "ball", "3000", "--seed", "5", "--headless", "--width", "64",
                                  "--height", "48", "--script", dir.write("explain.txt", script)});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  std::size_t agree = 0, routed = 0;
  for (std::size_t at = r.err.find("the backend agrees"); at != std::string::npos;
       at = r.err.find("the backend agrees", at + 1))
    ++agree;
  for (std::size_t at = r.err.find("refinement["); at != std::string::npos;
       at = r.err.find("refinement[", at + 1))
    ++routed;
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("instead"))) << r.err;
  EXPECT_GT(agree, 10u) << r.err;  // points still external before step 3 were explained...
  EXPECT_GT(routed, 5u) << r.err;  // ... several through a refinement entry
  EXPECT_THAT(r.err, HasSubstr("first distribution (section 3.1)"));
}

// The triangles of an OBJ as a set of vertex-coordinate triples, each rotated to start at its least
// vertex (orientation kept), so that two files with the same faces in another order compare equal.
std::set<std::array<std::string, 3>> obj_faces(const std::string& path) {
  std::vector<std::string> vertices;
  std::set<std::array<std::string, 3>> faces;
  for (const std::string& line : lines_of(path)) {
    if (line.rfind("v ", 0) == 0) vertices.push_back(line.substr(2));
    if (line.rfind("f ", 0) != 0) continue;
    std::istringstream in(line.substr(2));
    std::array<std::string, 3> f;
    for (auto& corner : f) {
      std::size_t index = 0;
      in >> index;
      corner = index >= 1 && index <= vertices.size() ? vertices[index - 1] : "?";
    }
    while (!(f[0] <= f[1] && f[0] <= f[2]))
      std::rotate(f.begin(), f.begin() + 1, f.end());
    faces.insert(f);
  }
  return faces;
}

// The sub-steps' count from the viewer's log ("sub-step K of N: ..."): the phases go up to
// "redistribution" (the step's result), and the one before it is the last edit.  -1 when not logged.
int substep_count(const std::string& log) {
  const std::size_t marker = log.find(": redistribution");
  if (marker == std::string::npos) return -1;
  const std::size_t of = log.rfind(" of ", marker);
  return of == std::string::npos ? -1 : std::stoi(log.substr(of + 4));
}

// Issue 6, item 3: the sub-step mode plays a step phase by phase on the mesh before it.  Replaying the
// engine's recorded refinements, swaps and removals in their order must end in the engine's own mesh; the
// first phase is the mesh before the step.
TEST(ViewerHeadless, SubStepsReplayTheStepToTheEnginesMesh) {
  TempDir dir;
  std::string script = "next-removal\nexport-mesh " + (dir / "result.obj") + "\n";
  for (int phase = 0; phase < 40; ++phase)
    script += "substep " + std::to_string(phase) + "\nexport-mesh " +
              (dir / ("phase_" + std::to_string(phase) + ".obj")) + "\n";
  // With the swaps layer, a phase shows only the swaps made so far (their sequence numbers, near white):
  // none at the refinement phase.
  script +=
      "hide hull\nhide wireframe\nhide internal\nhide external\nhide vertices\nshow swaps\nframe "
      "removal\nsubstep "
      "1\nscreenshot " +
      (dir / "refinement.png") + "\nsubstep off\nscreenshot " + (dir / "result.png") + "\n";
  const ViewerRun r = run_viewer({"--gen", "ball", "20", "--seed", "3", "--headless", "--width", "320",
                                  "--height", "240", "--script", dir.write("substeps.txt", script)});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("refinement: "));
  EXPECT_THAT(r.err, HasSubstr("(Fig. 4)"));  // a removal phase
  const int last = substep_count(r.err);
  ASSERT_GE(last, 3) << r.err;
  const auto result = obj_faces(dir / "result.obj");
  EXPECT_EQ(obj_faces(dir / ("phase_" + std::to_string(last - 1) + ".obj")), result);
  EXPECT_NE(obj_faces(dir / "phase_0.obj"), result);
  EXPECT_NE(obj_faces(dir / "phase_1.obj"), obj_faces(dir / "phase_0.obj"));
  auto swap_pixels = [](const Image& img) {
    std::size_t n = 0;
    for (const auto& p : img.rgb)
      n += rgba_near(p, pack_rgba(0.9f, 1.0f, 0.9f, 1.0f)) ? 1 : 0;
    return n;
  };
  EXPECT_EQ(swap_pixels(read_png(dir / "refinement.png")), 0u);
  EXPECT_GT(swap_pixels(read_png(dir / "result.png")), 0u);
}

// --engine auto picks as `cudahull hull` does (plan_hull()): on the CPU backend, the stepping engine.
TEST(ViewerHeadless, EngineAutoPicksAsTheCommandLine) {
  TempDir dir;
  ViewerRun r = run_viewer({"--gen", "ball", "2000", "--seed", "3", "--engine", "auto", "--backend", "cpu",
                            "--headless", "--width", "64", "--height", "48", "--steps", "2", "--screenshot",
                            dir / "shot.png"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("cpu"));
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("resident engine"))) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "shot.png"));
  ViewerRun bad = run_viewer({"--gen", "ball", "20", "--engine", "fastest", "--headless"});
  EXPECT_NE(bad.exit_code, 0) << describe(bad);
}

// Issue 15, deliverable 3: the debugger on the resident engine (--engine resident, its records read back
// each step).  Explain point ends where the engine put each point; the sub-steps replay a step with a
// removal to the engine's own mesh; next-rejected stops at the first step with a rejected foldover.
TEST(ViewerHeadless, ResidentEngineDebuggerViews) {
  TempDir dir;
  std::string script = "step 3\n";
  for (int i = 0; i < 3000; i += 10)
    script += "explain-point " + std::to_string(i) + "\n";
  ViewerRun r = run_viewer({"--gen", "ball", "3000", "--seed", "5", "--engine", "resident", "--headless",
                            "--width", "64", "--height", "48", "--script", dir.write("explain.txt", script)});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("resident engine"));
  std::size_t agree = 0;
  for (std::size_t at = r.err.find("the backend agrees"); at != std::string::npos;
       at = r.err.find("the backend agrees", at + 1))
    ++agree;
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("instead"))) << r.err;
  EXPECT_GT(agree, 10u) << r.err;
  EXPECT_THAT(r.err, HasSubstr("refinement at apex"));

  script = "next-removal\nexport-mesh " + (dir / "result.obj") + "\n";
  for (int phase = 0; phase < 60; ++phase)
    script += "substep " + std::to_string(phase) + "\nexport-mesh " +
              (dir / ("phase_" + std::to_string(phase) + ".obj")) + "\n";
  script += "substep off\nrewind 0\nnext-rejected\nexport-trace " + (dir / "trace.jsonl") + "\n";
  r = run_viewer({"--gen", "ball", "60", "--seed", "1", "--engine", "resident", "--headless", "--width", "64",
                  "--height", "48", "--script", dir.write("substeps.txt", script)});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("(Fig. 4)"));  // a removal phase
  const int last = substep_count(r.err);
  ASSERT_GE(last, 3) << r.err;
  ASSERT_LE(last, 60);
  const auto result = obj_faces(dir / "result.obj");
  EXPECT_EQ(obj_faces(dir / ("phase_" + std::to_string(last - 1) + ".obj")), result);
  EXPECT_NE(obj_faces(dir / "phase_0.obj"), result);
  const std::vector<std::string> trace = lines_of(dir / "trace.jsonl");
  ASSERT_FALSE(trace.empty());
  EXPECT_GT(nlohmann::json::parse(trace.back())["swaps_rejected"].get<int>(), 0) << r.err;
}

// The resident engine's exported result after an exact finish (a lattice, whose flat faces stop the local
// edits short) is the exact hull, not the last step's mesh (the scene shows the result once done).
TEST(ViewerHeadless, ResidentEngineExportsItsExactResult) {
  TempDir dir;
  write_points(dir / "grid.xyz", generate_points(Distribution::kGrid, 3000, 2));
  const std::vector<Point3d> points = read_points_double(dir / "grid.xyz").points;
  const BasicHullMesh<Point3d> exact = exact_hull(points);
  const ViewerRun r =
      run_viewer({dir / "grid.xyz", "--engine", "resident", "--headless", "--width", "64", "--height", "48",
                  "--script", dir.write("export.txt", "run\nexport-mesh " + (dir / "hull.obj") + "\n")});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  std::size_t faces = 0, vertices = 0;
  for (const std::string& line : lines_of(dir / "hull.obj")) {
    faces += line.rfind("f ", 0) == 0 ? 1 : 0;
    vertices += line.rfind("v ", 0) == 0 ? 1 : 0;
  }
  EXPECT_EQ(faces, exact.triangles.size()) << r.err;
  EXPECT_EQ(vertices, exact.vertex_ids.size()) << r.err;
}

TEST(ViewerHeadless, BadScriptLineExits2NamingTheLine) {
  TempDir dir;
  const std::string script =
      dir.write("bad.txt", "# a demo\nstep 2\njump 4\nscreenshot " + (dir / "x.png") + "\n");
  const ViewerRun r = run_viewer({kBunny, "--headless", "--script", script});
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("bad.txt:3: unknown command 'jump'"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;  // one line
  EXPECT_FALSE(fs::exists(dir / "x.png"));                              // checked before anything ran

  const std::string layer = dir.write("layer.txt", "hide hulls\n");
  const ViewerRun l = run_viewer({kBunny, "--headless", "--script", layer});
  EXPECT_EQ(l.exit_code, 2) << describe(l);
  EXPECT_THAT(l.err, HasSubstr("layer.txt:1:"));
  EXPECT_THAT(l.err, HasSubstr("wireframe"));  // lists the layers

  const std::string camera = dir.write("camera.txt", "step\ncamera {\"pitch\": 95}\n");
  const ViewerRun c = run_viewer({kBunny, "--headless", "--script", camera});
  EXPECT_EQ(c.exit_code, 2) << describe(c);
  EXPECT_THAT(c.err, HasSubstr("camera.txt:2: camera: \"pitch\" must be in [-89, 89]"));
}

TEST(ViewerHeadless, ErrorsHaveTheCliExitCodes) {
  TempDir dir;
  EXPECT_EQ(run_viewer({dir / "missing.ply", "--headless", "--screenshot", dir / "x.png"}).exit_code, 3);
  const std::string bad = dir.write("bad.xyz", "1 2 3\n4 nan 6\n");
  const ViewerRun b = run_viewer({bad, "--headless", "--screenshot", dir / "x.png"});
  EXPECT_EQ(b.exit_code, 3) << describe(b);
  EXPECT_THAT(b.err, HasSubstr("bad.xyz"));
  EXPECT_EQ(run_viewer({kBunny, "--headless"}).exit_code, 2);  // nothing to write
  EXPECT_EQ(run_viewer({"--headless", "--screenshot", dir / "x.png"}).exit_code, 2);
  EXPECT_EQ(run_viewer({"--gen", "donut", "10", "--headless", "--screenshot", dir / "x.png"}).exit_code, 2);
  EXPECT_EQ(
      run_viewer({kBunny, "--gen", "ball", "10", "--headless", "--screenshot", dir / "x.png"}).exit_code, 2);
  EXPECT_EQ(run_viewer({kBunny, "--headless", "--script", dir / "none.txt"}).exit_code, 3);
  EXPECT_EQ(run_viewer({kBunny, "--backend", "cuda", "--headless", "--screenshot", dir / "x.png"}).exit_code,
            4);
  const ViewerRun w =
      run_viewer({kBunny, "--headless", "--steps", "1", "--screenshot", dir / "no/such/dir/x.png"});
  EXPECT_EQ(w.exit_code, 1) << describe(w);
}

// --precision: the cube [-1,1]^3's corners plus a point 1e-12 outside each face's centre.  In double every
// one of those six is a hull vertex (14 vertices); in float they round onto the faces (8); auto is double for
// .xyz.  A bad value exits 2.
TEST(ViewerHeadless, PrecisionDoubleKeepsPointsThatFloatRoundsAway) {
  TempDir dir;
  std::string text;
  auto add = [&text](double x, double y, double z) {
    char line[128];
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", x, y, z);
    text += line;
  };
  for (int k = 0; k < 8; ++k)
    add(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1);
  const double out = 1 + 1e-12;
  add(out, 0.1, 0.2);
  add(-out, 0.2, 0.1);
  add(0.1, out, 0.2);
  add(0.2, -out, 0.1);
  add(0.1, 0.2, out);
  add(0.2, 0.1, -out);
  const std::string input = dir.write("cube.xyz", text);
  auto vertices = [&](const std::vector<std::string>& precision, const std::string& name) {
    const std::string mesh = dir / (name + ".obj");
    std::vector<std::string> args{input, "--headless", "--script",
                                  dir.write(name + ".txt", "run\nexport-mesh " + mesh + "\n")};
    args.insert(args.end(), precision.begin(), precision.end());
    const ViewerRun r = run_viewer(args);
    EXPECT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_THAT(r.err, HasSubstr("; precision " + (precision.empty() ? std::string("double (auto)")
                                                                     : precision[1] + " (as requested)")));
    int count = 0;
    for (const std::string& line : lines_of(mesh))
      count += line.rfind("v ", 0) == 0;
    return count;
  };
  EXPECT_EQ(vertices({"--precision", "double"}, "double"), 14);
  EXPECT_EQ(vertices({"--precision", "float"}, "float"), 8);
  EXPECT_EQ(vertices({}, "auto"), 14);

  const ViewerRun bad =
      run_viewer({input, "--headless", "--script", dir / "auto.txt", "--precision", "half"});
  EXPECT_EQ(bad.exit_code, 2) << describe(bad);
  EXPECT_THAT(bad.err, HasSubstr("--precision"));
}

TEST(ViewerWindow, StepsScreenshotAndCloseAfterFrames) {
  if (!has_display()) GTEST_SKIP() << "no display (run under xvfb-run, as scripts/test does)";
  TempDir dir;
  const std::string script =
      dir.write("win.txt", std::string(kHullOnly) + "step 5\nscreenshot " + (dir / "five.png") +
                               "\nrewind 1\n" + "screenshot " + (dir / "one.png") + "\n");
  const ViewerRun r =
      run_viewer({kBunny, "--width", "320", "--height", "240", "--script", script, "--frames", "3"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("CPU upload"));
  const Image five = read_png(dir / "five.png"), one = read_png(dir / "one.png");
  EXPECT_GT(five.width, 0);
  EXPECT_GT(variance(five), 1e-3);
  EXPECT_GT(central_fraction(five, hull_colored), 0.5);
  EXPECT_GT(differing_fraction(one, five), 0.05);

  // The command-line options, windowed: --steps then --screenshot, then 2 frames more.
  const ViewerRun o = run_viewer({"--gen", "ball", "5000", "--width", "256", "--height", "192", "--steps",
                                  "3", "--screenshot", dir / "opt.png", "--frames", "2"});
  ASSERT_EQ(o.exit_code, 0) << describe(o);
  EXPECT_GT(variance(read_png(dir / "opt.png")), 1e-3);
}

UiRect rect_of(const nlohmann::json& j) {
  return {j["x"].get<float>(), j["y"].get<float>(), j["width"].get<float>(), j["height"].get<float>()};
}

// Issue 17: the panels are docked to the window's edges, sized from it, at 1280x720 and 1920x1080 with
// every panel open (the debugger too): the rectangles Dear ImGui really drew (--ui-layout) lie inside the
// window, no two intersect, none covers the 3-d view, and no panel's content runs past its right edge.
TEST(ViewerWindow, PanelsAreDockedWithoutOverlapAtBothSizes) {
  if (!has_display()) GTEST_SKIP() << "no display (run under xvfb-run, as scripts/test does)";
  TempDir dir;
  const std::string script = dir.write("ui.txt", "step 3\nselect-face 0\nshow swaps\n");
  for (const auto& [width, height] : {std::pair{1280, 720}, std::pair{1920, 1080}}) {
    const std::string json_path = dir / ("layout_" + std::to_string(width) + ".json");
    const ViewerRun r =
        run_viewer({kBunny, "--width", std::to_string(width), "--height", std::to_string(height), "--script",
                    script, "--frames", "3", "--ui-layout", json_path});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    std::ifstream in(json_path);
    const nlohmann::json layout = nlohmann::json::parse(in);
    const float w = layout["window"]["width"].get<float>(), h = layout["window"]["height"].get<float>();
    EXPECT_EQ(w, static_cast<float>(width));
    EXPECT_EQ(h, static_cast<float>(height));
    std::vector<std::string> names;
    std::vector<UiRect> rects;
    for (const auto& p : layout["panels"]) {
      names.push_back(p["name"].get<std::string>());
      rects.push_back(rect_of(p));
      EXPECT_TRUE(rects.back().inside(w, h)) << names.back() << " at " << width << "x" << height;
      EXPECT_LE(p["overflow_x"].get<float>(), 0.5f)
          << names.back() << " is cut at " << width << "x" << height;
    }
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"Debugger", "Iteration", "Over the iterations", "cudahull"}));
    const UiRect view = rect_of(layout["view"]);
    EXPECT_TRUE(view.inside(w, h));
    EXPECT_GT(view.width * view.height, 0.25f * w * h);
    for (std::size_t a = 0; a < rects.size(); ++a) {
      EXPECT_FALSE(rects[a].intersects(view)) << names[a] << " covers the view";
      for (std::size_t b = a + 1; b < rects.size(); ++b)
        EXPECT_FALSE(rects[a].intersects(rects[b]))
            << names[a] << " and " << names[b] << " overlap at " << width << "x" << height;
    }
  }
}

// The same arithmetic over sizes the window test does not open: small, wide, high-DPI, debugger hidden.
TEST(ViewerParts, LayoutTilesTheWindowAtAnySize) {
  for (const auto& [w, h, scale] :
       {std::tuple{1280.f, 720.f, 1.f}, std::tuple{1920.f, 1080.f, 1.f}, std::tuple{800.f, 600.f, 1.f},
        std::tuple{3840.f, 2160.f, 2.f}, std::tuple{2560.f, 1080.f, 1.f}}) {
    for (bool debugger : {true, false}) {
      const UiLayout l = compute_ui_layout(w, h, scale, debugger);
      std::vector<UiRect> rects{l.controls, l.iteration, l.plots, l.view};
      if (debugger) rects.push_back(l.debugger);
      float area = 0;
      for (std::size_t a = 0; a < rects.size(); ++a) {
        EXPECT_TRUE(rects[a].inside(w, h)) << a << " at " << w << "x" << h;
        EXPECT_GT(rects[a].width, 0);
        area += rects[a].width * rects[a].height;
        for (std::size_t b = a + 1; b < rects.size(); ++b)
          EXPECT_FALSE(rects[a].intersects(rects[b])) << a << " and " << b << " at " << w << "x" << h;
      }
      EXPECT_FLOAT_EQ(area, w * h);  // the panels and the view tile the window
    }
  }
}

TEST(ViewerParts, CameraJsonRoundTripsAndRejectsBadValues) {
  Camera a;
  a.fit({-1, -2, -3}, {1, 2, 3});
  a.orbit(40, -25, 600);
  a.pan(10, 5, 600);
  a.zoom(2);
  Camera b;
  b.from_json(nlohmann::json::parse(a.to_json().dump()));
  EXPECT_EQ(a.to_json(), b.to_json());
  EXPECT_FLOAT_EQ(b.yaw(), a.yaw());

  Camera c = b;
  c.from_json({{"yaw", 10}});  // a subset changes only those keys
  EXPECT_FLOAT_EQ(c.yaw(), 10.0f);
  EXPECT_FLOAT_EQ(c.distance(), b.distance());
  EXPECT_THROW(c.from_json({{"distance", -1}}), std::invalid_argument);
  EXPECT_THROW(c.from_json({{"target", {1, 2}}}), std::invalid_argument);
  EXPECT_THROW(c.from_json({{"zoom", 2}}), std::invalid_argument);
  EXPECT_THROW(c.from_json(nlohmann::json::array()), std::invalid_argument);
  EXPECT_FLOAT_EQ(c.yaw(), 10.0f);  // unchanged by the failures

  a.reset();  // back to the view fit() chose
  Camera fitted;
  fitted.fit({-1, -2, -3}, {1, 2, 3});
  EXPECT_EQ(a.to_json(), fitted.to_json());
}

TEST(ViewerParts, ScriptParsing) {
  std::istringstream ok(
      "step\nstep 3  # three\n\n  run\nrewind 0\nselect-face 7\nshow cells\nhide hull\n"
      "camera {\"yaw\": 1}\nscreenshot out/a b.png\nset point-colors face\n");
  const auto commands = parse_script(ok, "ok.txt");
  ASSERT_EQ(commands.size(), 10u);
  EXPECT_EQ(commands[0].number, 1);
  EXPECT_EQ(commands[1].number, 3);
  EXPECT_EQ(commands[2].kind, ScriptCommand::Kind::kRun);
  EXPECT_EQ(commands[2].where, "ok.txt:4");
  EXPECT_EQ(commands[8].text, "out/a b.png");

  auto error_of = [](const std::string& text) {
    std::istringstream in(text);
    try {
      parse_script(in, "s");
    } catch (const ScriptError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error_of("step -1\n"), HasSubstr("s:1: 'step' needs a count"));
  EXPECT_THAT(error_of("step\nrewind\n"), HasSubstr("s:2: 'rewind' needs"));
  EXPECT_THAT(error_of("run 3\n"), HasSubstr("s:1: 'run' takes no argument"));
  EXPECT_THAT(error_of("camera {yaw}\n"), HasSubstr("s:1: 'camera' needs a JSON object"));
  EXPECT_THAT(error_of("set hull-opacity 2\n"), HasSubstr("s:1: hull-opacity must be a number in [0, 1]"));
  EXPECT_THAT(error_of("screenshot\n"), HasSubstr("s:1: 'screenshot' needs a PNG path"));
}

TEST(ViewerParts, NumberedPaths) {
  EXPECT_EQ(format_numbered_path("a/%d.png", 7), "a/7.png");
  EXPECT_EQ(format_numbered_path("a/s_%03d.png", 7), "a/s_007.png");
  EXPECT_EQ(format_numbered_path("a/plain.png", 7), "a/plain.png");
  EXPECT_EQ(format_numbered_path("100%_%d.png", 2), "100%_2.png");
  EXPECT_FALSE(has_number_field("a/%s.png"));
  EXPECT_TRUE(layer_from_name("wireframe").has_value());
  EXPECT_FALSE(layer_from_name("cell").has_value());
}

}  // namespace
}  // namespace cudahull::viewer
