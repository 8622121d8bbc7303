// The `cudahull` subcommands.  Each returns the process exit code (errors.hpp) or throws; main() maps
// exceptions to one line on stderr and the documented exit code.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cudahull::cli {

struct InfoOptions {
  std::string input;
};
int run_info(const InfoOptions& options);

struct GenOptions {
  std::string distribution;
  std::uint64_t count = 0;
  std::uint64_t seed = 1;
  std::string output;
};
int run_gen(const GenOptions& options);

struct HullOptions {
  std::string input;
  std::string output;        // -o: .obj, .off or .ply
  std::string vertices_out;  // --vertices-out
  std::string backend = "auto";
  std::string engine =
      "auto";  // --engine: "auto", "stepping" (the host edits the mesh) or "resident" (issue 15)
  // --precision: "auto" (the file's auto_precision(): double for text formats and double PLY, float for
  // binary float PLY), "float" or "double".
  std::string precision = "auto";
  bool verify = false;
  std::string stats;   // --stats FILE or "-"
  std::string trace;   // --trace FILE (JSON lines)
  bool table = false;  // --table: the per-iteration table on stdout
  bool quiet = false;
};
int run_hull(const HullOptions& options);

struct BenchOptions {
  std::string input;  // a file, or empty with --dist
  std::string distribution = "cube";
  std::uint64_t count = 1000000;
  std::uint64_t seed = 1;
  std::string backend = "auto";
  std::string engine = "auto";     // as for hull
  std::string precision = "auto";  // as for hull; "auto" is float for a generated distribution
  int repeat = 3;
  std::string versus;  // "qhull", "loop" (with batch) or empty
  bool json = false;
  // --batch B (issue 27): B clouds of `count` points of `distribution` through convex_hull_batch(); 0: one
  // cloud through the engines, as before.
  std::uint64_t batch = 0;
};
int run_bench(const BenchOptions& options);
// `bench --batch B` (bench_batch.cpp), which run_bench() hands a batch to.
int run_bench_batch(const BenchOptions& options);

struct CheckOptions {
  std::string points;              // any point file the CLI reads
  std::string hull;                // faces (.obj .off .ply, Qhull's `o` output) or a list of point ids
  std::string precision = "auto";  // as for hull: "auto" is the point file's
};
int run_check(const CheckOptions& options);

// The points of `path` in Point's precision (Point3 or Point3d): float as read_points() rounds them; double
// as the file gives them, any finite value.  `quiet`: no progress line on a terminal's stderr.
template <class Point>
std::vector<Point> read_input(const std::string& path, bool quiet);

}  // namespace cudahull::cli
