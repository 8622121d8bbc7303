// cudahull: exact 3D convex hulls with the CudaHull algorithm.  See README.md and `cudahull --help`.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "command_support.hpp"
#include "commands.hpp"
#include "cudahull/convex_hull.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/generators.hpp"
#include "cudahull/mesh_io.hpp"
#include "huge_pages.hpp"

namespace {

const char* kExitCodes =
    "Exit codes: 0 ok; 1 cannot write output; 2 usage; 3 unreadable or invalid input; 4 out of memory or\n"
    "device failure; 5 --verify found the hull wrong (check: HULL is not the hull).";

const char* kPrecisionHelp =
    "auto (the file's: double for .xyz .txt .obj .off and ascii or double PLY, float for binary float PLY "
    "and generated points), float or double";

const char* kEngineHelp =
    "auto (resident on a GPU, stepping on the CPU), stepping (Algorithm 1 an iteration at a time; the host "
    "edits the mesh, the backend moves the points) or resident (the whole iteration where the points are: "
    "on the GPU with a CUDA backend, else one host thread; with --trace or --table it steps an iteration at "
    "a time and reads back its records)";

const std::vector<std::string> kBackends = {"auto", "cuda", "cpu"};
const std::vector<std::string> kEngines = {"auto", "stepping", "resident"};
const std::vector<std::string> kPrecisions = {"auto", "float", "double"};

// An option that takes one of `choices`, its default shown in --help.
void add_choice(CLI::App* command, const std::string& name, std::string& value, const std::string& help,
                const std::vector<std::string>& choices) {
  command->add_option(name, value, help)->check(CLI::IsMember(choices))->capture_default_str();
}

int fail(int code, const std::string& message) {
  return cudahull::report_error("cudahull", code, message);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace cudahull;
  cli::use_huge_pages(argv);
  cli::pool_settings_from_environment();
  CLI::App app{
      "cudahull: exact 3D convex hulls with the CudaHull algorithm (Stein, Geva, El-Sana 2012).\n"
      "Points are read and computed as float32 or double (--precision); the hull is exact for those values."};
  app.footer(kExitCodes);
  app.require_subcommand(1);
  app.set_version_flag("--version", "cudahull 0.1.0");

  cli::InfoOptions info;
  auto* info_cmd = app.add_subcommand("info", "Print a point set's size and bounding box as one JSON object");
  info_cmd->add_option("FILE", info.input, "Input: .ply .obj .off .xyz .txt, or - for xyz on stdin")
      ->required();

  cli::GenOptions gen;
  std::string dist_help = "Distribution:";
  for (const auto& name : distribution_names())
    dist_help += " " + name;
  auto* gen_cmd = app.add_subcommand("gen", "Generate a synthetic point set");
  gen_cmd->add_option("DIST", gen.distribution, dist_help)->required();
  gen_cmd->add_option("N", gen.count, "Number of points")->required()->check(CLI::Range(1ull, 4000000000ull));
  gen_cmd->add_option("--seed", gen.seed, "Random seed (same seed, same points)")->capture_default_str();
  gen_cmd->add_option("-o,--output", gen.output, "Output: .ply (binary), .xyz, .txt, .obj or .off")
      ->required();

  cli::HullOptions hull;
  auto* hull_cmd = app.add_subcommand("hull", "Compute the exact convex hull of a point set");
  hull_cmd->add_option("INPUT", hull.input, "Input: .ply .obj .off .xyz .txt, or - for xyz on stdin")
      ->required();
  hull_cmd->add_option("-o,--output", hull.output, "Write the hull mesh: .obj, .off or .ply")
      ->check([](const std::string& path) { return mesh_path_problem(path); });  // before any work
  hull_cmd->add_option(
      "--vertices-out", hull.vertices_out,
      "Write the hull vertices, one 'index x y z' line each (0-based input indices, sorted)");
  add_choice(hull_cmd, "--backend", hull.backend, "auto (CUDA when a GPU is usable, else CPU), cuda or cpu",
             kBackends);
  add_choice(hull_cmd, "--engine", hull.engine, kEngineHelp, kEngines);
  add_choice(hull_cmd, "--precision", hull.precision, kPrecisionHelp, kPrecisions);
  hull_cmd->add_flag("--verify", hull.verify,
                     "Check the result with the independent exact checker (exit 5 if wrong)");
  hull_cmd->add_option("--stats", hull.stats, "Write counts and times as JSON to FILE, or - for stdout");
  hull_cmd->add_option("--trace", hull.trace,
                       "Write one JSON line per iteration (the IterationRecord) to FILE");
  hull_cmd->add_flag("--table", hull.table,
                     "Print the per-iteration table (cf. the paper's Fig. 9) on stdout");
  hull_cmd->add_flag("-q,--quiet", hull.quiet, "No progress or summary on stderr");

  cli::CheckOptions check;
  auto* check_cmd = app.add_subcommand(
      "check",
      "Check exactly that HULL, from any tool, is the convex hull of POINTS, as hull --verify does (exit 5 "
      "and the reasons if not)");
  check_cmd->add_option("POINTS", check.points, "The points: .ply .obj .off .xyz .txt, or - for xyz on stdin")
      ->required();
  check_cmd
      ->add_option(
          "HULL", check.hull,
          "The hull: faces as .obj, .off or .ply (polygons allowed; Qhull's `qhull o` output as .off; "
          "vertices matched to POINTS by exact coordinates, Qhull's within its 16 printed digits), or "
          "any other file of 0-based point ids, one a line ('id' or 'id x y z'), compared with the "
          "exact set of strictly extreme points")
      ->required();
  add_choice(check_cmd, "--precision", check.precision, kPrecisionHelp, kPrecisions);

  cli::BenchOptions bench;
  auto* bench_cmd = app.add_subcommand(
      "bench", "Time the hull against Qhull, as in the paper's Table 1 (--batch: many clouds in one call)");
  bench_cmd->add_option("INPUT", bench.input, "An input file instead of a generated distribution");
  bench_cmd->add_option("--dist", bench.distribution, dist_help)->capture_default_str();
  bench_cmd->add_option("--n", bench.count, "Number of generated points")->capture_default_str();
  bench_cmd->add_option("--seed", bench.seed, "Random seed")->capture_default_str();
  add_choice(bench_cmd, "--backend", bench.backend, "auto, cuda or cpu", kBackends);
  add_choice(bench_cmd, "--engine", bench.engine, kEngineHelp, kEngines);
  add_choice(bench_cmd, "--precision", bench.precision, kPrecisionHelp, kPrecisions);
  bench_cmd->add_option("--repeat", bench.repeat, "Runs to take the median of")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  bench_cmd
      ->add_option("--vs", bench.versus,
                   "Also run this reference in the same process: qhull; with --batch, qhull or loop (the "
                   "clouds one convex_hull() call at a time), each a loop over the clouds, compared cloud "
                   "for cloud")
      ->check(CLI::IsMember({"qhull", "loop"}));
  bench_cmd->add_flag("--json", bench.json, "Print one JSON object instead of the table row");
  bench_cmd
      ->add_option("--batch", bench.batch,
                   "Time convex_hull_batch() on this many clouds of --n points of --dist each (cloud c "
                   "from seed + c)")
      ->check(CLI::Range(1ull, 100000000ull));

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    return fail(kExitUsage, what + " (see cudahull --help)");
  }

  const int code = run_reporting_errors("cudahull", [&] {
    if (*info_cmd) return cli::run_info(info);
    if (*gen_cmd) return cli::run_gen(gen);
    if (*hull_cmd) return cli::run_hull(hull);
    if (*check_cmd) return cli::run_check(check);
    if (*bench_cmd) return cli::run_bench(bench);
    return static_cast<int>(kExitUsage);
  });
  // The device blocks the runs kept for reuse go back before exit, so that a leak checker
  // (compute-sanitizer --leak-check full) sees every allocation freed.  Nothing where no device was used.
  release_device_memory();
  return code;
}
