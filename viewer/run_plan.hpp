// What a run does on its own, from the command line: --steps, then --script, then --screenshot; one action
// per next() call, so the headless run loops over it and the window takes one action per frame (a script
// then plays as a visible demo).
//
//   no --script, --screenshot OUT:   step K (or run to the end without --steps), then one PNG;
//   no --script, OUT with %d:        a PNG at every position 0..K (or to the end), %d = the position;
//   --script FILE:                   step K if --steps, the script, then OUT if given (%d = the position).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "script.hpp"
#include "session.hpp"

namespace cudahull::viewer {

struct PlanOptions {
  std::optional<int> steps;
  std::vector<ScriptCommand> script;
  std::string screenshot;
  int width = 1280, height = 800;  // screenshots, in pixels
};

class RunPlan {
 public:
  explicit RunPlan(PlanOptions options) : o_(std::move(options)) {}
  // Does the next action; returns false once nothing is left.  Log lines go to `log` (may be empty).
  // Throws what Session::execute throws.
  bool next(Session& session, std::string& log);
  bool finished() const { return stage_ == Stage::kFinished; }

 private:
  enum class Stage { kSteps, kScript, kSequence, kScreenshot, kFinished };
  ScriptCommand shot() const;
  PlanOptions o_;
  Stage stage_ = Stage::kSteps;
  std::size_t script_index_ = 0;
  bool sequence_shot_taken_ = false;
};

}  // namespace cudahull::viewer
