// Scripts for reproducible demos and tests (`--script FILE`): one command per line, `#` starts a comment,
// blank lines are skipped.
//
//   step [N]             N iterations (default 1)
//   run                  to the end
//   rewind N             to timeline position N (steps from the start; 0 is the bare point set)
//   select-face ID       remember a face of the current polyhedron (drawn from issue 6 on)
//   show LAYER           hull, wireframe, internal, external, vertices (cells, swaps: reserved)
//   hide LAYER
//   camera JSON          the view, as Ctrl-C copies it (camera.hpp)
//   screenshot PATH      a PNG of the scene (not the panels); %d in PATH becomes the position
//   set NAME VALUE       point-size, point-opacity, hull-opacity, wire-width (numbers),
//                        point-colors state|face, face-colors state|age
//
// parse_script() checks the whole file before anything runs, so a bad line fails early with a one-line
// ScriptError naming the file and the line ("demo.txt:7: ...").
#pragma once

#include <istream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace cudahull::viewer {

class ScriptError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ScriptCommand {
  enum class Kind { kStep, kRun, kRewind, kSelectFace, kShow, kHide, kCamera, kScreenshot, kSet };
  Kind kind = Kind::kStep;
  long long number = 0;  // step, rewind, select-face
  std::string text;      // layer, path, or the setting's name
  std::string value;     // set: the value as written
  nlohmann::json json;   // camera
  std::string where;     // "FILE:LINE", for errors while running
};

std::vector<ScriptCommand> parse_script(std::istream& in, const std::string& name);
std::vector<ScriptCommand> read_script(const std::string& path);  // InputError when unreadable

}  // namespace cudahull::viewer
