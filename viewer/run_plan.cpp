#include "run_plan.hpp"

#include "png.hpp"

namespace cudahull::viewer {

ScriptCommand RunPlan::shot() const {
  ScriptCommand c;
  c.kind = ScriptCommand::Kind::kScreenshot;
  c.text = o_.screenshot;
  c.where = "--screenshot";
  return c;
}

bool RunPlan::next(Session& session, std::string& log) {
  log.clear();
  Scene* scene = session.scene();
  const bool sequence = o_.script.empty() && has_number_field(o_.screenshot);
  switch (stage_) {
    case Stage::kSteps:
      stage_ = sequence ? Stage::kSequence : o_.script.empty() ? Stage::kScreenshot : Stage::kScript;
      if (sequence) return true;
      // Through the session, which records a frame per step while recording.
      if (scene && o_.steps) session.step(*o_.steps);
      // Without a script, a screenshot shows the end unless --steps says otherwise.
      if (scene && !o_.steps && o_.script.empty() && !o_.screenshot.empty()) session.run_to_end();
      return true;
    case Stage::kScript:
      if (script_index_ < o_.script.size()) {
        log = session.execute(o_.script[script_index_++], o_.width, o_.height);
        return true;
      }
      stage_ = Stage::kScreenshot;
      return true;
    case Stage::kSequence: {
      // Shoot at the current position, then step; stop after K steps or at the end.
      if (!sequence_shot_taken_) {
        log = session.execute(shot(), o_.width, o_.height);
        sequence_shot_taken_ = true;
        return true;
      }
      const bool more = scene && !scene->done() && (!o_.steps || scene->position() < *o_.steps);
      if (!more) {
        stage_ = Stage::kFinished;
        return false;
      }
      session.step(1);
      sequence_shot_taken_ = false;
      return true;
    }
    case Stage::kScreenshot:
      stage_ = Stage::kFinished;
      if (!o_.screenshot.empty()) log = session.execute(shot(), o_.width, o_.height);
      return true;
    case Stage::kFinished:
      return false;
  }
  return false;
}

}  // namespace cudahull::viewer
