// PNG screenshots: stb_image_write into memory, then cudahull::write_file_atomically (a temporary name and a
// rename), so a reader never sees half a picture.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cudahull::viewer {

// `rgba` is width * height * 4 bytes, top row first; the PNG is RGB (alpha dropped).  Throws OutputError.
void write_png(const std::string& path, const std::vector<std::uint8_t>& rgba, int width, int height);

// `pattern` with its first %d (or %0Nd) replaced by `number`; unchanged when it has none.
std::string format_numbered_path(const std::string& pattern, int number);
bool has_number_field(const std::string& pattern);

}  // namespace cudahull::viewer
