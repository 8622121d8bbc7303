#include "png.hpp"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

#include <cstdio>
#include <ostream>

#include "cudahull/errors.hpp"
#include "cudahull/mesh_io.hpp"

namespace cudahull::viewer {

namespace {

// Where the %d or %0Nd field is: [begin, end), or begin == npos.
std::pair<std::size_t, std::size_t> number_field(const std::string& s) {
  for (std::size_t i = 0; i + 1 < s.size(); ++i) {
    if (s[i] != '%') continue;
    std::size_t j = i + 1;
    if (s[j] == '0')
      while (j < s.size() && s[j] >= '0' && s[j] <= '9')
        ++j;
    if (j < s.size() && s[j] == 'd') return {i, j + 1};
  }
  return {std::string::npos, 0};
}

}  // namespace

bool has_number_field(const std::string& pattern) {
  return number_field(pattern).first != std::string::npos;
}

std::string format_numbered_path(const std::string& pattern, int number) {
  const auto [begin, end] = number_field(pattern);
  if (begin == std::string::npos) return pattern;
  char digits[32];
  std::snprintf(digits, sizeof digits, pattern.substr(begin, end - begin).c_str(), number);
  return pattern.substr(0, begin) + digits + pattern.substr(end);
}

void write_png(const std::string& path, const std::vector<std::uint8_t>& rgba, int width, int height) {
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * height * 3);
  for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i) {
    rgb[3 * i] = rgba[4 * i];
    rgb[3 * i + 1] = rgba[4 * i + 1];
    rgb[3 * i + 2] = rgba[4 * i + 2];
  }
  std::string png;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &png, width, height, 3, rgb.data(), width * 3))
    throw OutputError(path + ": cannot encode the PNG");
  write_file_atomically(
      path, [&](std::ostream& out) { out.write(png.data(), static_cast<std::streamsize>(png.size())); });
}

}  // namespace cudahull::viewer
