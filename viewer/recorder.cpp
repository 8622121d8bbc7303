#include "recorder.hpp"

#include <csignal>
#include <cstdlib>
#include <filesystem>

#include "cudahull/errors.hpp"

namespace cudahull::viewer {

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s)
    out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

bool is_recording_path(const std::string& path) {
  return ends_with(path, ".mp4") || ends_with(path, ".gif");
}

Recorder::Recorder(const std::string& path, int width, int height, double fps)
    : path_(path), width_(width), height_(height) {
  if (!is_recording_path(path)) throw OutputError(path + ": a recording is a .mp4 or a .gif");
  if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
    throw OutputError(path + ": cannot record: no ffmpeg on the PATH (Debian: apt-get install ffmpeg)");
  // A broken pipe (ffmpeg gone) must be an error here, not the end of the viewer.
  std::signal(SIGPIPE, SIG_IGN);
  const bool gif = ends_with(path, ".gif");
  temporary_ = path + ".partial";
  char size[64], rate[32];
  std::snprintf(size, sizeof size, "%dx%d", width, height);
  std::snprintf(rate, sizeof rate, "%g", fps);
  // H.264 in yuv420p (what players take) needs even sizes; a GIF gets one palette made for the clip.
  const std::string filter =
      gif ? "split[a][b];[a]palettegen=stats_mode=diff[p];[b][p]paletteuse" : "pad=ceil(iw/2)*2:ceil(ih/2)*2";
  const std::string codec = gif ? "-f gif" : "-c:v libx264 -pix_fmt yuv420p -movflags +faststart -f mp4";
  const std::string command =
      std::string("ffmpeg -hide_banner -loglevel error -y -f rawvideo -pix_fmt rgba -s ") + size +
      " -framerate " + rate + " -i - -vf " + shell_quote(filter) + " " + codec + " " +
      shell_quote(temporary_);
  pipe_ = popen(command.c_str(), "w");
  if (pipe_ == nullptr) throw OutputError(path + ": cannot start ffmpeg");
}

Recorder::~Recorder() {
  if (pipe_ == nullptr) return;
  pclose(pipe_);
  std::error_code ec;
  std::filesystem::remove(temporary_, ec);
}

void Recorder::add(const std::vector<std::uint8_t>& rgba) {
  if (pipe_ == nullptr) return;
  if (std::fwrite(rgba.data(), 1, rgba.size(), pipe_) != rgba.size())
    throw OutputError(path_ + ": ffmpeg stopped taking frames");
  ++frames_;
}

int Recorder::close() {
  if (pipe_ == nullptr) return frames_;
  const int status = pclose(pipe_);
  pipe_ = nullptr;
  std::error_code ec;
  if (status != 0 || frames_ == 0) {
    std::filesystem::remove(temporary_, ec);
    throw OutputError(path_ + (frames_ == 0
                                   ? ": no frames recorded (nothing stepped while recording)"
                                   : ": ffmpeg failed (exit status " + std::to_string(status) + ")"));
  }
  std::filesystem::rename(temporary_, path_, ec);
  if (ec) throw OutputError(path_ + ": " + ec.message());
  return frames_;
}

}  // namespace cudahull::viewer
