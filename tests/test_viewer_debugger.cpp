// cudahull-viewer's debugger views, headless: next-rejected and the swaps and refinement layers against the
// exported trace and decision table, the demos in demos/ and the cases they show, explain point, the
// sub-steps replaying a step to the engine's mesh, and the same on the resident engine.  Label: gl.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cudahull/exact_hull.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/point_io.hpp"
#include "cudahull/point_writer.hpp"
#include "overlay.hpp"
#include "support/viewer_run.hpp"

namespace cudahull::viewer {
namespace {

// Issue 6, Figs. 3-5 and 7: next-rejected stops at a step that rejected a swap; the swaps layer draws that
// step's swaps (green new edges) and the rejected foldover (orange old edge, magenta beneath-triangle); the
// refinement layer changes the picture; the exported decision table is the trace's decision array for the
// step, entry by entry; the exported mesh has the step's faces.
TEST(ViewerHeadless, SwapsRefinementAndExportsMatchTheTrace) {
  TempDir dir;
  const std::string script =
      dir.write("debug.txt",
                "next-rejected\nhide internal\nhide external\nhide hull\nhide wireframe\nhide vertices\n"
                "screenshot " +
                    (dir / "plain.png") + "\nshow swaps\nscreenshot " + (dir / "swaps.png") +
                    "\nhide swaps\nshow refinement\nscreenshot " + (dir / "refinement.png") +
                    "\nexport-trace " + (dir / "trace.jsonl") + "\nexport-decisions " +
                    (dir / "decisions.csv") + "\nexport-mesh " + (dir / "mesh.obj") + "\n");
  const ViewerRun r = run_viewer({"--gen", "ball", "3000", "--seed", "5", "--headless", "--width", "320",
                                  "--height", "240", "--script", script});
  ASSERT_EQ(r.exit_code, 0) << describe(r);

  const std::vector<std::string> trace = lines_of(dir / "trace.jsonl");
  ASSERT_FALSE(trace.empty());
  const nlohmann::json step = nlohmann::json::parse(trace.back());
  EXPECT_GT(step["swaps_rejected"].get<int>(), 0) << "next-rejected stopped at a step without a rejection";
  for (std::size_t k = 0; k + 1 < trace.size(); ++k)
    EXPECT_EQ(nlohmann::json::parse(trace[k])["swaps_rejected"].get<int>(), 0)
        << "an earlier rejection at " << k;

  const std::vector<std::string> csv = lines_of(dir / "decisions.csv");
  const nlohmann::json& decisions = step["decisions"];
  ASSERT_EQ(csv.size(), decisions.size() + 1);  // header
  for (std::size_t k = 0; k < decisions.size(); ++k) {
    const nlohmann::json& d = decisions[k];
    std::istringstream row(csv[k + 1]);
    std::vector<std::string> cells;
    for (std::string cell; std::getline(row, cell, ',');)
      cells.push_back(cell);
    ASSERT_GE(cells.size(), 7u) << csv[k + 1];
    EXPECT_EQ(cells[0], std::to_string(k));
    EXPECT_EQ(cells[1], d["kind"].get<std::string>());
    if (d["kind"] == "swap") {
      EXPECT_DOUBLE_EQ(std::stod(cells[2]), d["plane"][0].get<double>()) << k;
      EXPECT_DOUBLE_EQ(std::stod(cells[5]), d["plane"][3].get<double>()) << k;
    }
  }

  std::size_t faces = 0;
  for (const std::string& line : lines_of(dir / "mesh.obj"))
    faces += line.rfind("f ", 0) == 0 ? 1 : 0;
  EXPECT_EQ(faces, step["faces_after"].get<std::size_t>());

  const Image plain = read_png(dir / "plain.png"), swaps = read_png(dir / "swaps.png"),
              refinement = read_png(dir / "refinement.png");
  auto count = [](const Image& img, std::uint32_t rgba) {
    std::size_t n = 0;
    for (const auto& p : img.rgb)
      n += rgba_near(p, rgba) ? 1 : 0;
    return n;
  };
  EXPECT_GT(count(swaps, kRegularSwapRgba), 20u);
  EXPECT_GT(count(swaps, kFoldoverRgba) + count(swaps, kBeneathRgba), 5u);
  // The sequence numbers beside the swaps (seven-segment digits, near white).
  EXPECT_GT(count(swaps, pack_rgba(0.9f, 1.0f, 0.9f, 1.0f)), 10u);
  EXPECT_EQ(count(plain, kRegularSwapRgba) + count(plain, kBeneathRgba), 0u);
  EXPECT_GT(differing_fraction(plain, refinement), 0.01);
}

// Issue 6, item 7: every demo in demos/ renders headless, and each really contains its case (from the
// trace it exports): a regular swap (Fig. 3), a rejected foldover with its vertex beneath (Fig. 5), a
// removal after complementary swaps (Fig. 4), and the bunny's whole run (Fig. 10).
TEST(ViewerHeadless, DemosRenderAndShowTheirCases) {
  TempDir dir;
  fs::create_directory_symlink(CUDAHULL_ASSETS_DIR, dir / "assets");
  fs::create_directories(dir / "out/demos");  // as scripts/demos does: a screenshot never makes folders
  std::string last_log;
  auto run_demo = [&](const std::string& name) {
    const std::string path = std::string(CUDAHULL_DEMOS_DIR) + "/" + name + ".txt";
    std::ifstream in(path);
    std::string first;
    std::getline(in, first);
    const std::string prefix = "# cudahull-viewer ";
    EXPECT_EQ(first.rfind(prefix, 0), 0u) << path << " does not start with its input";
    std::vector<std::string> args;
    std::istringstream words(first.substr(prefix.size()));
    for (std::string w; words >> w;)
      args.push_back(w);
    for (std::string a : {"--headless", "--width", "320", "--height", "240", "--script"})
      args.push_back(a);
    args.push_back(path);
    const ViewerRun r = run_viewer(args, dir / "");
    EXPECT_EQ(r.exit_code, 0) << name << ": " << describe(r);
    last_log = r.err;
    const std::vector<std::string> trace =
        lines_of(dir / ("out/demos/" + name.substr(0, name.find('_')) + ".jsonl"));
    return trace.empty() ? nlohmann::json() : nlohmann::json::parse(trace.back());
  };
  auto has_swap = [](const nlohmann::json& step, const std::string& kind) {
    for (const auto& w : step["swaps"])
      if (w["kind"] == kind && (kind != "rejected_foldover" || w.contains("beneath_vertex"))) return true;
    return false;
  };

  const nlohmann::json swap = run_demo("swap_fig3");
  EXPECT_TRUE(has_swap(swap, "regular"));
  EXPECT_GT(differing_fraction(read_png(dir / "out/demos/swap_1_refinement.png"),
                               read_png(dir / "out/demos/swap_3_swaps.png")),
            0.01);

  EXPECT_TRUE(has_swap(run_demo("foldover_fig5"), "rejected_foldover"));
  // `frame rejected` names the case and says whether a later edit of the step resolved it.
  EXPECT_THAT(last_log, HasSubstr("lies beneath"));
  EXPECT_THAT(last_log, ::testing::AnyOf(HasSubstr("resolved later"), HasSubstr("not resolved")));
  EXPECT_GT(variance(read_png(dir / "out/demos/foldover.png")), 1e-3);

  const nlohmann::json removal = run_demo("removal_fig4");
  EXPECT_TRUE(has_swap(removal, "complementary"));
  bool removed = false;
  for (const auto& m : removal["removals"])
    removed = removed || !m["rejected"].get<bool>();
  EXPECT_TRUE(removed);
  EXPECT_GT(variance(read_png(dir / "out/demos/removal.png")), 1e-3);

  const nlohmann::json bunny = run_demo("bunny_fig10");
  EXPECT_EQ(bunny["external_after"].get<std::size_t>(), 0u) << "the bunny demo runs to the end";
  for (const char* png : {"bunny_00.png", "bunny_01.png", "bunny_05.png"})
    EXPECT_GT(variance(read_png(dir / ("out/demos/" + std::string(png)))), 1e-4) << png;
  // Issue 17: one animation per demo beside its pictures: the bunny's iterations, the others' sub-steps.
  EXPECT_EQ(decoded_frames(dir / "out/demos/bunny.gif"), bunny["iteration"].get<int>() + 1);
  for (const char* gif : {"swap.gif", "foldover.gif", "removal.gif"})
    EXPECT_GE(decoded_frames(dir / ("out/demos/" + std::string(gif))), 4) << gif;
}

// Issue 6, item 4: "explain point" retraces a point's route through the step's refinement[] and decision[]
// (Fig. 7) to a face or "internal"; for every point it must end where the backend put the point.
TEST(ViewerHeadless, ExplainPointEndsWhereTheBackendPutThePoint) {
  TempDir dir;
  std::string script = "step 3\n";
  for (int i = 0; i < 60; ++i)
    script += "explain-point " + std::to_string(i) + "\n";
  script += "rewind 1\nexplain-point 7\nscreenshot " + (dir / "x.png") + "\n";
  const ViewerRun r = run_viewer({"--gen", "ball", "3000", "--seed", "5", "--headless", "--width", "64",
                                  "--height", "48", "--script", dir.write("explain.txt", script)});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  std::size_t agree = 0, routed = 0;
  for (std::size_t at = r.err.find("the backend agrees"); at != std::string::npos;
       at = r.err.find("the backend agrees", at + 1))
    ++agree;
  for (std::size_t at = r.err.find("refinement["); at != std::string::npos;
       at = r.err.find("refinement[", at + 1))
    ++routed;
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("instead"))) << r.err;
  EXPECT_GT(agree, 10u) << r.err;  // points still external before step 3 were explained...
  EXPECT_GT(routed, 5u) << r.err;  // ... several through a refinement entry
  EXPECT_THAT(r.err, HasSubstr("first distribution (section 3.1)"));
}

// The triangles of an OBJ as a set of vertex-coordinate triples, each rotated to start at its least
// vertex (orientation kept), so that two files with the same faces in another order compare equal.
std::set<std::array<std::string, 3>> obj_faces(const std::string& path) {
  std::vector<std::string> vertices;
  std::set<std::array<std::string, 3>> faces;
  for (const std::string& line : lines_of(path)) {
    if (line.rfind("v ", 0) == 0) vertices.push_back(line.substr(2));
    if (line.rfind("f ", 0) != 0) continue;
    std::istringstream in(line.substr(2));
    std::array<std::string, 3> f;
    for (auto& corner : f) {
      std::size_t index = 0;
      in >> index;
      corner = index >= 1 && index <= vertices.size() ? vertices[index - 1] : "?";
    }
    while (!(f[0] <= f[1] && f[0] <= f[2]))
      std::rotate(f.begin(), f.begin() + 1, f.end());
    faces.insert(f);
  }
  return faces;
}

// The sub-steps' count from the viewer's log ("sub-step K of N: ..."): the phases go up to
// "redistribution" (the step's result), and the one before it is the last edit.  -1 when not logged.
int substep_count(const std::string& log) {
  const std::size_t marker = log.find(": redistribution");
  if (marker == std::string::npos) return -1;
  const std::size_t of = log.rfind(" of ", marker);
  return of == std::string::npos ? -1 : std::stoi(log.substr(of + 4));
}

// Issue 6, item 3: the sub-step mode plays a step phase by phase on the mesh before it.  Replaying the
// engine's recorded refinements, swaps and removals in their order must end in the engine's own mesh; the
// first phase is the mesh before the step.
TEST(ViewerHeadless, SubStepsReplayTheStepToTheEnginesMesh) {
  TempDir dir;
  std::string script = "next-removal\nexport-mesh " + (dir / "result.obj") + "\n";
  for (int phase = 0; phase < 40; ++phase)
    script += "substep " + std::to_string(phase) + "\nexport-mesh " +
              (dir / ("phase_" + std::to_string(phase) + ".obj")) + "\n";
  // With the swaps layer, a phase shows only the swaps made so far (their sequence numbers, near white):
  // none at the refinement phase.
  script +=
      "hide hull\nhide wireframe\nhide internal\nhide external\nhide vertices\nshow swaps\nframe "
      "removal\nsubstep "
      "1\nscreenshot " +
      (dir / "refinement.png") + "\nsubstep off\nscreenshot " + (dir / "result.png") + "\n";
  const ViewerRun r = run_viewer({"--gen", "ball", "20", "--seed", "3", "--headless", "--width", "320",
                                  "--height", "240", "--script", dir.write("substeps.txt", script)});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("refinement: "));
  EXPECT_THAT(r.err, HasSubstr("(Fig. 4)"));  // a removal phase
  const int last = substep_count(r.err);
  ASSERT_GE(last, 3) << r.err;
  const auto result = obj_faces(dir / "result.obj");
  EXPECT_EQ(obj_faces(dir / ("phase_" + std::to_string(last - 1) + ".obj")), result);
  EXPECT_NE(obj_faces(dir / "phase_0.obj"), result);
  EXPECT_NE(obj_faces(dir / "phase_1.obj"), obj_faces(dir / "phase_0.obj"));
  auto swap_pixels = [](const Image& img) {
    std::size_t n = 0;
    for (const auto& p : img.rgb)
      n += rgba_near(p, pack_rgba(0.9f, 1.0f, 0.9f, 1.0f)) ? 1 : 0;
    return n;
  };
  EXPECT_EQ(swap_pixels(read_png(dir / "refinement.png")), 0u);
  EXPECT_GT(swap_pixels(read_png(dir / "result.png")), 0u);
}

// Issue 15, deliverable 3: the debugger on the resident engine (--engine resident, its records read back
// each step).  Explain point ends where the engine put each point; the sub-steps replay a step with a
// removal to the engine's own mesh; next-rejected stops at the first step with a rejected foldover.
TEST(ViewerHeadless, ResidentEngineDebuggerViews) {
  TempDir dir;
  std::string script = "step 3\n";
  for (int i = 0; i < 3000; i += 10)
    script += "explain-point " + std::to_string(i) + "\n";
  ViewerRun r = run_viewer({"--gen", "ball", "3000", "--seed", "5", "--engine", "resident", "--headless",
                            "--width", "64", "--height", "48", "--script", dir.write("explain.txt", script)});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("resident engine"));
  std::size_t agree = 0;
  for (std::size_t at = r.err.find("the backend agrees"); at != std::string::npos;
       at = r.err.find("the backend agrees", at + 1))
    ++agree;
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("instead"))) << r.err;
  EXPECT_GT(agree, 10u) << r.err;
  EXPECT_THAT(r.err, HasSubstr("refinement at apex"));

  script = "next-removal\nexport-mesh " + (dir / "result.obj") + "\n";
  for (int phase = 0; phase < 60; ++phase)
    script += "substep " + std::to_string(phase) + "\nexport-mesh " +
              (dir / ("phase_" + std::to_string(phase) + ".obj")) + "\n";
  script += "substep off\nrewind 0\nnext-rejected\nexport-trace " + (dir / "trace.jsonl") + "\n";
  r = run_viewer({"--gen", "ball", "60", "--seed", "1", "--engine", "resident", "--headless", "--width", "64",
                  "--height", "48", "--script", dir.write("substeps.txt", script)});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_THAT(r.err, HasSubstr("(Fig. 4)"));  // a removal phase
  const int last = substep_count(r.err);
  ASSERT_GE(last, 3) << r.err;
  ASSERT_LE(last, 60);
  const auto result = obj_faces(dir / "result.obj");
  EXPECT_EQ(obj_faces(dir / ("phase_" + std::to_string(last - 1) + ".obj")), result);
  EXPECT_NE(obj_faces(dir / "phase_0.obj"), result);
  const std::vector<std::string> trace = lines_of(dir / "trace.jsonl");
  ASSERT_FALSE(trace.empty());
  EXPECT_GT(nlohmann::json::parse(trace.back())["swaps_rejected"].get<int>(), 0) << r.err;
}

// The resident engine's exported result after an exact finish (a lattice, whose flat faces stop the local
// edits short) is the exact hull, not the last step's mesh (the scene shows the result once done).
TEST(ViewerHeadless, ResidentEngineExportsItsExactResult) {
  TempDir dir;
  write_points(dir / "grid.xyz", generate_points(Distribution::kGrid, 3000, 2));
  const std::vector<Point3d> points = read_points_double(dir / "grid.xyz").points;
  const BasicHullMesh<Point3d> exact = exact_hull(points);
  const ViewerRun r =
      run_viewer({dir / "grid.xyz", "--engine", "resident", "--headless", "--width", "64", "--height", "48",
                  "--script", dir.write("export.txt", "run\nexport-mesh " + (dir / "hull.obj") + "\n")});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  std::size_t faces = 0, vertices = 0;
  for (const std::string& line : lines_of(dir / "hull.obj")) {
    faces += line.rfind("f ", 0) == 0 ? 1 : 0;
    vertices += line.rfind("v ", 0) == 0 ? 1 : 0;
  }
  EXPECT_EQ(faces, exact.triangles.size()) << r.err;
  EXPECT_EQ(vertices, exact.vertex_ids.size()) << r.err;
}

}  // namespace
}  // namespace cudahull::viewer
