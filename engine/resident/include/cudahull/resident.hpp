// The resident engine (issue 15): Algorithm 1 with the mesh, the edits and the routing all where the points
// are, the host hearing O(1) bytes a step until the result.  resident_hull_host() runs it on the host (one
// thread, the reference for the device); cuda/resident_cuda.hpp runs the same operations on the GPU.
// docs/architecture.md, "The resident engine", says how it differs from the stepping Engine.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cudahull/types.hpp"

namespace cudahull {

// The phases of a resident run, as its host clock sees them: P and the first mesh (setup); the launches
// that mark the faces to refine and find their furthest points (refine); the swap rounds, where the host
// waits for them apart (rounds: recording only); the launches that split, swap and route to the end of an
// iteration, fused (route); the exact check and the result (finish); and the host's own work between them,
// growing buffers (host).
enum class ResidentPhase { kSetup, kRefine, kRounds, kRoute, kFinish, kHost, kCount };
inline constexpr const char* kResidentPhaseNames[] = {"setup", "refine", "rounds", "route", "finish", "host"};

// How fast the executor's hardware can go: memory bandwidth (measured with a large copy, counting its read
// and its write), and the cost of a launch and of a wait for a value from the executor (measured with empty
// ones; zero on the host executor, whose operations are plain calls).
struct HardwarePace {
  double bytes_per_ms = 0;
  double launch_ms = 0, wait_ms = 0;
};

// One phase's distance to the hardware: its time, the bytes it moves at least (a lower bound modelled from
// the sizes it works on: every point read once by the setup; the kept points' coordinates, index and face
// read and written once by a routing; the mesh's corners and links once by refinement, rounds and finish),
// its launches and waits, and the least time those could take: the larger of the bytes at the bandwidth and
// the launches and waits at their latency.
struct PhaseStat {
  double ms = 0;
  std::uint64_t bytes = 0, launches = 0, host_waits = 0;
  double floor_ms = 0;
};

// What a resident run did, and what it cost in traffic between host and executor.
struct ResidentStats {
  std::uint64_t iterations = 0;
  std::uint64_t refined_faces = 0;
  std::uint64_t rounds = 0;               // swap and removal rounds over all iterations
  std::uint64_t edits = 0;                // swaps and removals made
  std::uint64_t work_items = 0;           // faces the rounds looked at, summed over the rounds
  std::uint64_t dropped_by_polytope = 0;  // points proven inside P, the extremes' polytope, at the start
  std::uint64_t loop_iterations = 0;      // iterations run by the device loop of a small mesh
  std::uint64_t round_overflows = 0;      // runs of rounds that stopped short of room (the host grew it)
  bool polytope_first = false;            // P was the first mesh (else section 3.1's tetrahedron)
  std::uint64_t faults = 0;  // defects after the rounds: concave edges, thin vertices (then repaired)
  std::uint64_t repaired_patches = 0;   // patches of defects repaired where they are (fault_repair.hpp)
  std::uint64_t repair_vertices = 0;    // the vertices of the patches the repairs looked at, every attempt
  bool exact_finish = false;            // the result came from the exact reference hull of the candidates
  std::string note;                     // why, for lower-dimensional input or the exact finish
  std::uint64_t host_syncs = 0;         // waits for the executor with a value coming back
  std::uint64_t bytes_to_device = 0;    // host -> executor, after the points
  std::uint64_t bytes_from_device = 0;  // executor -> host, the result included
  std::uint64_t device_bytes_peak = 0;  // device memory held at most, the points included (0 on the host)
  std::uint64_t points_read_back = 0;   // coordinates read back for the exact checks (borrowed points only)
  // Where the time went (host clock; each phase ends in a wait for a count, so these are wall times).
  double setup_ms = 0, refine_ms = 0, rounds_ms = 0, route_ms = 0, finish_ms = 0;
  // Inside the device's rounds (device clock, the slowest block): finding and claiming, judging the
  // claims, numbering the winners, applying.  Zero on the host.
  double round_phase_ms[4] = {0, 0, 0, 0};
  // Every phase of the run (ResidentPhase order), the hardware's pace they are measured against, and the
  // run's wall time, which the phases' times add up to.
  PhaseStat phases[static_cast<int>(ResidentPhase::kCount)];
  HardwarePace pace;
  double total_ms = 0;
};

// Each phase's floor at `pace` (PhaseStat), and the pace itself, into `stats`: asked by whoever reports a run
// once it is over, so that no run pays for measuring the hardware.
inline void fill_floors(ResidentStats& stats, const HardwarePace& pace) {
  stats.pace = pace;
  for (PhaseStat& p : stats.phases) {
    const double moving = pace.bytes_per_ms > 0 ? static_cast<double>(p.bytes) / pace.bytes_per_ms : 0;
    const double waiting =
        static_cast<double>(p.launches) * pace.launch_ms + static_cast<double>(p.host_waits) * pace.wait_ms;
    p.floor_ms = moving > waiting ? moving : waiting;
  }
}

// The host executor's pace: this thread's memory bandwidth, measured once a process (the best of three
// copies of 32 MiB, each a read and a write); an operation is a plain call, with no launch or wait to pay.
HardwarePace host_pace();

// Each phase with its name: visit(name, const PhaseStat&), in ResidentPhase order (bench --json "phases").
template <class Visit>
void for_each_phase(const ResidentStats& s, Visit&& visit) {
  for (int p = 0; p < static_cast<int>(ResidentPhase::kCount); ++p)
    visit(kResidentPhaseNames[p], s.phases[p]);
}

// Every field of the stats with its name, in declaration order: visit(name, value) with a std::uint64_t,
// bool, std::string, double or const double (&)[4].  The CLI's JSON and the Python module's dict are made
// from it, so a field added here shows in both.
template <class Visit>
void for_each_stat(const ResidentStats& s, Visit&& visit) {
  visit("iterations", s.iterations);
  visit("refined_faces", s.refined_faces);
  visit("rounds", s.rounds);
  visit("edits", s.edits);
  visit("work_items", s.work_items);
  visit("dropped_by_polytope", s.dropped_by_polytope);
  visit("loop_iterations", s.loop_iterations);
  visit("round_overflows", s.round_overflows);
  visit("polytope_first", s.polytope_first);
  visit("faults", s.faults);
  visit("repaired_patches", s.repaired_patches);
  visit("repair_vertices", s.repair_vertices);
  visit("exact_finish", s.exact_finish);
  visit("note", s.note);
  visit("host_syncs", s.host_syncs);
  visit("bytes_to_device", s.bytes_to_device);
  visit("bytes_from_device", s.bytes_from_device);
  visit("device_bytes_peak", s.device_bytes_peak);
  visit("points_read_back", s.points_read_back);
  visit("setup_ms", s.setup_ms);
  visit("refine_ms", s.refine_ms);
  visit("rounds_ms", s.rounds_ms);
  visit("route_ms", s.route_ms);
  visit("finish_ms", s.finish_ms);
  visit("round_phase_ms", s.round_phase_ms);
}

// Which paths of the driver the host executor takes: kHost, an iteration a launch (the reference); kDevice,
// the GPU executor's (with few points left, a device loop of iterations with its own room checks; the
// small finish in one step).  Both run the same iteration (iteration.hpp) and give the same mesh; the tests
// compare them.
enum class ResidentPath { kHost, kDevice };

// The exact hull (vertices are exactly the strictly extreme points), computed by the resident engine's
// operations on the host.  Point3 or Point3d.  `executor_points_only`: the driver reads coordinates only
// through the executor, as it does for points that only the GPU holds (ResidentCudaHull::use_device_points).
template <class Point>
BasicHullMesh<Point> resident_hull_host(const std::vector<Point>& points, ResidentStats* stats = nullptr,
                                        ResidentPath path = ResidentPath::kHost,
                                        bool executor_points_only = false);

// The clouds small_hull_host() takes.  Its cost grows with vertices times faces: on a sphere (every point a
// vertex) it loses to the stepping engine from about 150 points on, where on a ball it still wins
// (docs/benchmarks.md, "The measurements behind the code's constants").
inline constexpr std::size_t kSmallHullPoints = 128;

// The exact hull of `count` points (4..kSmallHullPoints) on the calling thread by the batch warps' hull
// (resident/small_hull.hpp on HostTeam, its workspace kept per thread): the batch kernel's mesh for the
// cloud, face for face.  False (mesh untouched) for another count, a flat cloud or one small_hull() hands
// on: the caller takes another path.  Coordinates in the fast exact range (a float's always are).
template <class Point>
bool small_hull_host(const Point* points, std::size_t count, BasicHullMesh<Point>& mesh);

class SteppingEngine;

// The resident engine one iteration a step, with records (the viewer, `--trace`, `--table`: swaps with their
// kinds, rejected foldovers with the vertex beneath, removals, the decision array), on the host executor;
// cuda/resident_cuda.hpp makes the GPU's.  The same hull as resident_hull_host(); the engine borrows
// `points`.
template <class Point>
std::unique_ptr<SteppingEngine> make_resident_stepping_engine(const std::vector<Point>& points);

}  // namespace cudahull
