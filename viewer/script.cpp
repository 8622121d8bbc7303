#include "script.hpp"

#include <cctype>
#include <charconv>
#include <fstream>
#include <sstream>

#include "cudahull/errors.hpp"
#include "recorder.hpp"
#include "renderer.hpp"

namespace cudahull::viewer {

namespace {

std::string trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b])))
    ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1])))
    --e;
  return s.substr(b, e - b);
}

bool parse_integer(const std::string& s, long long& out) {
  const char* end = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(s.data(), end, out);
  return ec == std::errc() && ptr == end;
}

bool parse_number(const std::string& s, double& out) {
  std::istringstream in(s);
  in >> out;
  return in && (in >> std::ws).eof();
}

const char* kSettings[] = {"point-size",  "point-opacity", "hull-opacity", "wire-width", "point-colors",
                           "face-colors", "point-mode",    "legend",       "record-fps"};

}  // namespace

std::vector<ScriptCommand> parse_script(std::istream& in, const std::string& name) {
  std::vector<ScriptCommand> commands;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string where = name + ":" + std::to_string(number);
    auto fail = [&](const std::string& why) { throw ScriptError(where + ": " + why); };
    // A '#' starts a comment, except inside camera JSON, where it cannot occur anyway.
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    line = trim(line);
    if (line.empty()) continue;
    const auto space = line.find_first_of(" \t");
    const std::string verb = line.substr(0, space);
    const std::string rest = space == std::string::npos ? "" : trim(line.substr(space));

    ScriptCommand c;
    c.where = where;
    auto one_integer = [&](long long min, const char* what) {
      if (rest.empty()) fail("'" + verb + "' needs " + what);
      if (!parse_integer(rest, c.number) || c.number < min)
        fail("'" + verb + "' needs " + what + ", not '" + rest + "'");
    };
    auto layer = [&] {
      if (rest.empty() || !layer_from_name(rest))
        fail("'" + verb + "' needs a layer (" + layer_names() + "), not '" + rest + "'");
      c.text = rest;
    };
    if (verb == "step") {
      c.kind = ScriptCommand::Kind::kStep;
      c.number = 1;
      if (!rest.empty()) one_integer(0, "a count of steps >= 0");
    } else if (verb == "run") {
      c.kind = ScriptCommand::Kind::kRun;
      if (!rest.empty()) fail("'run' takes no argument");
    } else if (verb == "rewind") {
      c.kind = ScriptCommand::Kind::kRewind;
      one_integer(0, "a timeline position >= 0");
    } else if (verb == "select-face") {
      c.kind = ScriptCommand::Kind::kSelectFace;
      one_integer(-1, "a face id (-1 clears)");
    } else if (verb == "show" || verb == "hide") {
      c.kind = verb == "show" ? ScriptCommand::Kind::kShow : ScriptCommand::Kind::kHide;
      layer();
    } else if (verb == "camera") {
      c.kind = ScriptCommand::Kind::kCamera;
      try {
        c.json = nlohmann::json::parse(rest);
      } catch (const nlohmann::json::exception&) {
        fail("'camera' needs a JSON object such as {\"yaw\": 30, \"pitch\": -20}");
      }
      if (!c.json.is_object()) fail("'camera' needs a JSON object");
    } else if (verb == "screenshot") {
      c.kind = ScriptCommand::Kind::kScreenshot;
      if (rest.empty()) fail("'screenshot' needs a PNG path");
      c.text = rest;
    } else if (verb == "next-rejected") {
      c.kind = ScriptCommand::Kind::kNextRejected;
      if (!rest.empty()) fail("'next-rejected' takes no argument");
    } else if (verb == "next-removal") {
      c.kind = ScriptCommand::Kind::kNextRemoval;
      if (!rest.empty()) fail("'next-removal' takes no argument");
    } else if (verb == "substep") {
      c.kind = ScriptCommand::Kind::kSubstep;
      if (rest == "off") {
        c.number = -1;
      } else if (rest == "all") {
        c.number = kAllSubsteps;
      } else {
        one_integer(0, "a phase number >= 0, or off");
      }
    } else if (verb == "hover" || verb == "click") {
      c.kind = verb == "hover" ? ScriptCommand::Kind::kHover : ScriptCommand::Kind::kClick;
      std::istringstream words(rest);
      std::string extra;
      double y = 0;
      if (!(words >> c.number >> c.value) || !parse_number(c.value, y) || c.number < 0 || y < 0 ||
          (words >> extra))
        fail("'" + verb + "' needs a pixel: X Y (from the top left)");
    } else if (verb == "record") {
      const auto space = rest.find_first_of(" \t");
      const std::string what = rest.substr(0, space);
      const std::string path = space == std::string::npos ? "" : trim(rest.substr(space));
      if (what == "start") {
        c.kind = ScriptCommand::Kind::kRecordStart;
        if (!is_recording_path(path)) fail("'record start' needs a .mp4 or .gif path, not '" + path + "'");
        c.text = path;
      } else if (what == "stop" && path.empty()) {
        c.kind = ScriptCommand::Kind::kRecordStop;
      } else {
        fail("'record' takes 'start PATH' or 'stop'");
      }
    } else if (verb == "explain-point") {
      c.kind = ScriptCommand::Kind::kExplainPoint;
      one_integer(0, "a point index");
    } else if (verb == "frame") {
      c.kind = ScriptCommand::Kind::kFrame;
      std::istringstream words(rest);
      std::string extra;
      words >> c.text;
      if (c.text == "swap") {
        if (!(words >> c.number) || c.number < 0) fail("'frame swap' needs a swap's sequence number");
      } else if (c.text != "rejected" && c.text != "removal") {
        fail("'frame' needs rejected, removal or swap SEQ, not '" + rest + "'");
      }
      if (words >> extra) fail("'frame' takes rejected, removal or swap SEQ");
    } else if (verb == "export-mesh" || verb == "export-trace" || verb == "export-decisions") {
      c.kind = verb == "export-mesh"    ? ScriptCommand::Kind::kExportMesh
               : verb == "export-trace" ? ScriptCommand::Kind::kExportTrace
                                        : ScriptCommand::Kind::kExportDecisions;
      if (rest.empty()) fail("'" + verb + "' needs a path");
      c.text = rest;
    } else if (verb == "set") {
      c.kind = ScriptCommand::Kind::kSet;
      std::istringstream words(rest);
      words >> c.text >> c.value;
      std::string extra;
      if (c.text.empty() || c.value.empty() || (words >> extra))
        fail("'set' needs a name and a value, e.g. 'set point-size 4'");
      double x = 0;
      if (c.text == "point-colors") {
        if (c.value != "state" && c.value != "face") fail("point-colors is 'state' or 'face'");
      } else if (c.text == "point-mode") {
        if (c.value != "auto" && c.value != "points" && c.value != "splats")
          fail("point-mode is 'auto', 'points' or 'splats'");
      } else if (c.text == "record-fps") {
        if (!parse_number(c.value, x) || x <= 0 || x > 120) fail("record-fps must be a number in (0, 120]");
      } else if (c.text == "legend") {
        if (c.value != "on" && c.value != "off") fail("legend is 'on' or 'off'");
      } else if (c.text == "face-colors") {
        if (c.value != "state" && c.value != "age") fail("face-colors is 'state' or 'age'");
      } else if (c.text == "point-size" && c.value == "auto") {
      } else if (c.text == "point-size" || c.text == "wire-width") {
        if (!parse_number(c.value, x) || x <= 0 || x > 64) fail(c.text + " must be a number in (0, 64]");
      } else if (c.text == "point-opacity" || c.text == "hull-opacity") {
        if (!parse_number(c.value, x) || x < 0 || x > 1) fail(c.text + " must be a number in [0, 1]");
      } else {
        std::string names;
        for (const char* s : kSettings)
          names += (names.empty() ? "" : ", ") + std::string(s);
        fail("unknown setting '" + c.text + "' (" + names + ")");
      }
    } else {
      fail("unknown command '" + verb +
           "' (step, run, rewind, select-face, show, hide, camera, screenshot, set, next-rejected, "
           "next-removal, frame, "
           "export-mesh, export-trace, export-decisions, record, hover, click)");
    }
    commands.push_back(std::move(c));
  }
  return commands;
}

std::vector<ScriptCommand> read_script(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the script");
  return parse_script(in, path);
}

}  // namespace cudahull::viewer
