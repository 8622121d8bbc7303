// small_hull_host(): the batch warps' hull (small_hull.hpp) on HostTeam, for small clouds on the CPU.
//
// design:
//   workspace  per thread, grown to the largest cloud seen and reused: a slot with small_hull_room(n) (room
//              for every point a vertex, so a cloud never runs out of it), the cloud's six words a point, the
//              output's words and coordinates, and the cloud staged in double (as a warp stages it: the
//              tests convert once, not at every predicate)
//   run        small_hull() as a warp runs it: every count and list a prefix sum in index order, so the
//              mesh is the batch kernel's for the cloud, face for face
//   result     the output's faces (in slot order) and vertices (in index order) as a BasicHullMesh; false
//              where small_hull() hands the cloud on (flat, or a horizon it cannot follow): the caller's
//              other path
#include <cstdint>
#include <vector>

#include "cudahull/resident.hpp"
#include "cudahull/resident/small_hull.hpp"

namespace cudahull {

namespace {

using resident::u32;
using resident::u64;

struct SmallHullWorkspace {
  std::vector<u32> fv, fn, fv_spare, fn_spare, replaced_by, revisit, flags, face_rank, list, point_words,
      words;
  std::vector<u64> extreme;
  std::vector<Point3d> staged, coordinates;
  resident::RoundsState state{};
  u32 points = 0;  // the cloud size the arrays have room for

  void reserve(u32 n) {
    if (n <= points) return;
    const resident::BatchRoom room = resident::small_hull_room(n);
    for (auto* b : {&fv, &fn, &fv_spare, &fn_spare})
      b->resize(3 * std::size_t{room.faces});
    for (auto* b : {&replaced_by, &revisit, &flags, &face_rank})
      b->resize(room.faces + 1);
    extreme.resize(room.faces);
    list.resize(room.work);
    point_words.resize(6 * std::size_t{n});
    // A closed mesh of at most n vertices: at most 2 n - 4 faces of 3 words, then the vertex list.
    words.resize(7 * std::size_t{n} + 16);
    staged.resize(n);
    coordinates.resize(n);
    points = n;
  }
  resident::BatchSlot slot() {
    const resident::BatchRoom room = resident::small_hull_room(points);
    return resident::BatchSlot{
        fv.data(),      fn.data(),    fv_spare.data(),  fn_spare.data(), replaced_by.data(),
        revisit.data(), flags.data(), face_rank.data(), nullptr,         nullptr,
        extreme.data(), nullptr,      nullptr,          list.data(),     nullptr,
        &state,         room};
  }
};

}  // namespace

template <class Point>
bool small_hull_host(const Point* points, std::size_t count, BasicHullMesh<Point>& mesh) {
  if (count < 4 || count > kSmallHullPoints) return false;
  thread_local SmallHullWorkspace w;
  const u32 n = static_cast<u32>(count);
  w.reserve(n);
  for (u32 i = 0; i < n; ++i)
    w.staged[i] = Point3d{points[i].x, points[i].y, points[i].z};
  u32* words = w.point_words.data();
  const resident::BatchCloud<Point3d> cloud{
      w.staged.data(), n, words, words + n, words + 2 * n, words + 3 * n, words + 4 * n, words + 5 * n};
  u32 used[2] = {0, 0};
  const resident::BatchOutput<Point3d> out{w.words.data(), w.coordinates.data(), used,
                                           static_cast<u32>(w.words.size()),
                                           static_cast<u32>(w.coordinates.size())};
  resident::BatchResult result{};
  resident::small_hull(resident::HostTeam{}, w.slot(), cloud, out, &result);
  if (result.status != resident::kBatchDone) return false;
  const u32* corners = w.words.data() + result.word_at;
  const u32* ids = corners + 3 * std::size_t{result.faces};
  mesh.dimension = 3;
  mesh.vertex_ids.assign(ids, ids + result.vertices);
  mesh.vertices.resize(result.vertices);
  for (u32 k = 0; k < result.vertices; ++k)
    mesh.vertices[k] = points[ids[k]];
  mesh.triangles.resize(result.faces);
  for (u32 f = 0; f < result.faces; ++f)
    mesh.triangles[f] = {corners[3 * f], corners[3 * f + 1], corners[3 * f + 2]};
  mesh.polygon.clear();
  return true;
}

template bool small_hull_host(const Point3*, std::size_t, HullMesh&);
template bool small_hull_host(const Point3d*, std::size_t, HullMeshd&);

}  // namespace cudahull
