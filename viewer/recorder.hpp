// Recordings (issue 17): frames piped as raw RGBA into Debian's ffmpeg, which writes an H.264 .mp4 or a
// palette-optimised .gif.  The file appears under its name only when complete (ffmpeg writes a temporary
// name; close() renames it), as the screenshots do.
//
// Contract: open() checks that ffmpeg can be run and throws OutputError (naming the path) when it cannot,
// or for a name that ends in neither .mp4 nor .gif; add() takes frames of the size given to open(), top row
// first; close() waits for ffmpeg and throws OutputError if it failed.  The destructor closes quietly.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace cudahull::viewer {

class Recorder {
 public:
  Recorder(const std::string& path, int width, int height, double fps);
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  void add(const std::vector<std::uint8_t>& rgba);
  // Finishes the file; returns the number of frames in it.
  int close();

  const std::string& path() const { return path_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int frames() const { return frames_; }

 private:
  std::string path_, temporary_;
  int width_, height_;
  int frames_ = 0;
  std::FILE* pipe_ = nullptr;
};

// Whether `path` names a recording the Recorder writes (.mp4 or .gif).
bool is_recording_path(const std::string& path);

}  // namespace cudahull::viewer
