// Scripts for reproducible demos and tests (`--script FILE`): one command per line, `#` starts a comment,
// blank lines are skipped.
//
//   step [N]             N iterations (default 1)
//   run                  to the end
//   rewind N             to timeline position N (steps from the start; 0 is the bare point set)
//   select-face ID       select a face of the current polyhedron (the cells layer draws its cell)
//   show LAYER           hull, wireframe, internal, external, vertices, cells, swaps, normals, refinement
//   hide LAYER
//   next-rejected        to the next position whose step rejected a swap (stays put if none)
//   next-removal         to the next position whose step removed a vertex after complementary swaps
//   frame CASE           point the camera at a case of the step: rejected, removal, or swap SEQ
//   explain-point I      log how the step routed input point I through refinement[] and decision[]
//   substep K|off|all    show phase K of the step (0 before it, 1 refinement, then each swap or removal,
//                        last the redistribution); off shows the step's result; all plays every phase
//   record start PATH    record a .mp4 or .gif (ffmpeg): one frame per step, sub-step or jump from here on
//   record stop          finish the recording
//   hover X Y            log what the mouse at pixel (X, Y) of the screenshot size shows as its tooltip
//   click X Y            a click there: explain the point, or select the face (and show its cell)
//   export-mesh PATH     the current polyhedron (.obj, .off or .ply)
//   export-trace PATH    every step so far as JSON lines (`cudahull hull --trace`)
//   export-decisions PATH  the current step's decision array as CSV
//   camera JSON          the view, as Ctrl-C copies it (camera.hpp)
//   screenshot PATH      a PNG of the scene (not the panels); %d in PATH becomes the position
//   set NAME VALUE       point-size, point-opacity, hull-opacity, wire-width (numbers),
//                        point-colors state|face, face-colors state|age, point-mode auto|points|splats,
//                        legend on|off (the colour key drawn into the picture), record-fps N
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
  enum class Kind {
    kStep,
    kRun,
    kRewind,
    kSelectFace,
    kShow,
    kHide,
    kCamera,
    kScreenshot,
    kSet,
    kNextRejected,
    kNextRemoval,
    kFrame,
    kExplainPoint,
    kSubstep,
    kExportMesh,
    kExportTrace,
    kExportDecisions,
    kRecordStart,
    kRecordStop,
    kHover,
    kClick,
  };
  Kind kind = Kind::kStep;
  long long number = 0;  // step, rewind, select-face
  std::string text;      // layer, path, or the setting's name
  std::string value;     // set: the value as written
  nlohmann::json json;   // camera
  std::string where;     // "FILE:LINE", for errors while running
};

inline constexpr long long kAllSubsteps = -2;  // `substep all`

std::vector<ScriptCommand> parse_script(std::istream& in, const std::string& name);
std::vector<ScriptCommand> read_script(const std::string& path);  // InputError when unreadable

}  // namespace cudahull::viewer
