// The viewer's CUDA-GL interop path on the GPU machine (issue 5, item 8): a headless EGL context on the
// NVIDIA GPU, the CUDA backend writing per-point state straight into the GL buffer.  The picture must be
// the one the CPU-upload path draws for the same step, pixel for pixel, and no per-point data may come back
// from the device while stepping.  Label: gpu (needs a CUDA device and an EGL driver on it).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include "cudahull/generators.hpp"
#include "headless_context.hpp"
#include "loader.hpp"
#include "renderer.hpp"
#include "session.hpp"

namespace cudahull::viewer {
namespace {

struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgba;
};

Image shoot(Session& session, const std::string& name) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  session.screenshot(path, 320, 240);
  Image image;
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &image.width, &image.height, &channels, 4);
  EXPECT_NE(data, nullptr) << path;
  if (data) image.rgba.assign(data, data + 4 * image.width * image.height);
  stbi_image_free(data);
  std::filesystem::remove(path);
  return image;
}

std::size_t differing_pixels(const Image& a, const Image& b) {
  std::size_t count = 0;
  for (std::size_t i = 0; i + 3 < a.rgba.size() && i + 3 < b.rgba.size(); i += 4) {
    if (a.rgba[i] != b.rgba[i] || a.rgba[i + 1] != b.rgba[i + 1] || a.rgba[i + 2] != b.rgba[i + 2]) ++count;
  }
  return count;
}

TEST(ViewerInterop, SamePictureAsTheCpuUploadAndNoPerPointReadback) {
  auto context = HeadlessContext::create();
  std::string note;
  const auto factory = backend_factory("cuda", &note);
  const auto points =
      std::make_shared<const std::vector<Point3>>(generate_points(Distribution::kBall, 200000, 7));

  Session interop, upload;
  for (Session* s : {&interop, &upload}) {  // the points alone: their colours are what interop writes
    s->settings().show(Layer::kHull, false);
    s->settings().show(Layer::kWireframe, false);
  }
  interop.set_scene(std::make_unique<Scene>(points, factory, "ball"), true);
  upload.allow_interop(false);
  upload.set_scene(std::make_unique<Scene>(points, factory, "ball"), true);
  ASSERT_TRUE(interop.interop_active()) << interop.upload_path() << " (" << context->description() << ")";
  ASSERT_EQ(interop.upload_path(), "CUDA-GL interop");
  ASSERT_FALSE(upload.interop_active());

  Image first, last;
  for (int position : {1, 3, 6}) {
    interop.scene()->rewind(position);
    upload.scene()->rewind(position);
    const Image a = shoot(interop, "interop_" + std::to_string(position) + ".png");
    const Image b = shoot(upload, "upload_" + std::to_string(position) + ".png");
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    EXPECT_EQ(differing_pixels(a, b), 0u) << "position " << position;
    if (first.rgba.empty()) first = a;
    last = a;
  }
  // The compute splats (the default for large clouds) read the same buffer: the same picture again.
  for (Session* s : {&interop, &upload})
    s->settings().point_mode = PointMode::kSplats;
  EXPECT_EQ(differing_pixels(shoot(interop, "interop_splats.png"), shoot(upload, "upload_splats.png")), 0u);
  // External points (brown) turn internal (red) between the first distribution and step 6: the colours the
  // backend wrote really follow the stepping.
  EXPECT_GT(differing_pixels(first, last), 1000u) << "the picture changes";
  // The interop path read nothing per point back; the upload path did (n int32 per refresh).
  EXPECT_EQ(interop.scene()->point_readback_bytes(), 0u);
  EXPECT_GE(upload.scene()->point_readback_bytes(), points->size() * sizeof(std::int32_t));
  // Everything the backend sent to the host is the per-iteration O(faces) traffic in the records.
  std::uint64_t per_iteration = 0;
  for (const IterationRecord& r : interop.scene()->history())
    per_iteration += r.bytes_from_backend;
  EXPECT_EQ(interop.scene()->engine().bytes_from_backend(), per_iteration);
}

}  // namespace
}  // namespace cudahull::viewer
