// The resident engine's finish: the exact check once no point is left outside, the defects repaired where
// they are (fault_repair.hpp), the result read back, and the exact finish when that fails.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "cudahull/exact_hull.hpp"
#include "cudahull/mesh.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/resident.hpp"
#include "cudahull/resident/fault_repair.hpp"
#include "cudahull/resident/resident_buffers.hpp"

namespace cudahull::resident {

template <class Point, class Exec>
class ResidentFinish : protected ResidentBuffers<Point, Exec> {
  using Buffers = ResidentBuffers<Point, Exec>;

 protected:
  using Buffers::active_, Buffers::c_, Buffers::exec_, Buffers::face_rank_, Buffers::faces_, Buffers::fetch,
      Buffers::flags_, Buffers::fn_, Buffers::fv_, Buffers::fv_out_, Buffers::gather, Buffers::host_,
      Buffers::hull_of, Buffers::index_, Buffers::keep_, Buffers::replaced_by_, Buffers::listed,
      Buffers::revisit_, Buffers::n_, Buffers::point_rank_, Buffers::repair_rows_, Buffers::state_,
      Buffers::view, Buffers::work_list_;
  using Buffers::Buffers;

  // The mesh's faces, read back once.
  std::vector<u32> corners() {
    std::vector<u32> fv(3 * faces_);
    exec_.download(fv.data(), fv_.data(), fv.size());
    return fv;
  }

  // No point left outside: the result, the defects the rounds left repaired where they are first
  // (fault_repair.hpp), with more rings around them while some remain; the exact finish after the last,
  // or as soon as the patches would cover most of the mesh (repair_faults()).
  static constexpr std::array<u32, 3> kRepairRings{2, 4, 8};
  BasicHullMesh<Point> finish(ResidentStats& stats) {
    u32 faults = 0;
    bool checked = false;
    const char* stopped = "";
    for (std::size_t attempt = 0;; ++attempt) {
      std::optional<BasicHullMesh<Point>> out = finish_once(faults, checked);
      if (out) return std::move(*out);
      if (attempt == 0) stats.faults = faults;
      if (active_ != 0 || attempt == kRepairRings.size()) break;
      const std::optional<std::size_t> repaired =
          repair_faults(kRepairRings[attempt], checked, stats.repair_vertices);
      if (!repaired) {
        stopped = ", their patches most of the mesh";
        break;
      }
      stats.repaired_patches += *repaired;
    }
    return exact_finish(
        stats, std::to_string(stats.faults) + " concave edges or vertices not strictly extreme" +
                   (stats.repaired_patches ? ", " + std::to_string(faults) + " left after repair" : "") +
                   stopped);
  }

  // The result when no edge is concave and every vertex is strictly extreme (flat edges only triangulate
  // coplanar facets); otherwise nothing, and the defects in `faults`.
  // `checked`: the mesh is known to have none (a repair checked its faces), and is not counted again.
  std::optional<BasicHullMesh<Point>> finish_once(u32& faults, bool checked) {
    if constexpr (Exec::kFinishFaces > 0) {
      if (faces_ <= Exec::kFinishFaces) return finish_small(faults, checked);
    }
    // The edges that are not strictly convex, counted into the state; then the vertices in index order
    // (ascending, as exact_hull gives them) with the corners renumbered to their ranks, where they are.
    // Fewer corners than points (most hulls): the corners sorted without repeats, each corner found there
    // by bisection, and both counts read at once.  Otherwise each vertex flagged among the points and the
    // flags prefix-summed (no sort of a corner list larger than the points).  Only the result comes back.
    PhaseLaps laps("resident_finish");  // CUDAHULL_PHASE_TIMES=1
    RoundsState* st = state_.data();
    exec_.fill(&st->faults, 2, u32{0});
    if (!checked) exec_.for_each(faces_, CountFaults<Point>{view(), &st->faults});
    const std::size_t n = n_, corners = 3 * faces_;
    u32 counts[2] = {0, 0};  // faults, vertices
    const bool sorted = corners < n;
    if (sorted) {
      // The vertex list right after the renumbered corners, so that both come back in one read: fv_out_
      // grown for it (a spare: nothing in it is kept), as the face capacity may be only a little above
      // the faces in use.
      index_[1].grow(corners);
      fv_out_.grow(corners + std::min(corners, n));
      u32* list = fv_out_.data() + corners;
      exec_.sort_unique_to(fv_.data(), corners, list, index_[1].data(), n, &st->vertices);
      exec_.for_each(corners, FindCorners{fv_.data(), list, &st->vertices, fv_out_.data()});
    }
    exec_.download(counts, &st->faults, sorted ? 2 : 1);
    laps.lap("count");
    faults = counts[0] == 0 ? 0 : defects();
    if (faults != 0) return std::nullopt;
    if (sorted) {
      std::vector<u32> both(corners + counts[1]);
      exec_.download(both.data(), fv_out_.data(), both.size());
      return result_mesh(both.data(), counts[1], fv_out_.data() + corners);
    }
    keep_.grow(n);
    point_rank_.grow(n);
    index_[1].grow(n);
    exec_.fill(keep_.data(), n, u32{0});
    exec_.for_each(corners, FlagCorners{fv_.data(), keep_.data()});
    counts[1] = exec_.select(keep_.data(), point_rank_.data(), index_[1].data(), n);
    fv_out_.grow(corners);
    exec_.for_each(corners, RenumberCorners{fv_.data(), point_rank_.data(), fv_out_.data()});
    laps.lap("flag and select");
    const u32* vertex_list = index_[1].data();
    const u32 vertices = counts[1];
    BasicHullMesh<Point> out;
    resize_populated(out.vertex_ids, vertices);
    laps.lap("vertex list made");
    exec_.download(out.vertex_ids.data(), vertex_list, vertices);
    laps.lap("vertex list read");
    resize_populated(out.triangles, faces_);
    laps.lap("triangles made");
    static_assert(sizeof(Triangle) == 3 * sizeof(u32));
    exec_.download(reinterpret_cast<u32*>(out.triangles.data()), fv_out_.data(), 3 * faces_);
    laps.lap("triangles read");
    out.vertices = vertex_coordinates(out.vertex_ids, vertex_list);
    laps.lap("coordinates");
    return out;
  }

  // finish() of a small mesh in one launch and, as a rule, one read (the executor's finish_small): the
  // counts, the renumbered corners and the vertex list lie one after another in fv_out_, and the host reads
  // as many vertices as a closed mesh of genus 0 has (F / 2 + 2, Euler's formula), the rest only if there
  // are more.
  std::optional<BasicHullMesh<Point>> finish_small(u32& faults, bool checked) {
    const std::size_t corners = 3 * faces_, at = 2 + corners;
    // A spare (nothing in it is kept), whose size follows the live faces: room for the counts, the corners
    // and a list of up to as many vertices as corners.
    fv_out_.grow(at + corners);
    u32* out = fv_out_.data();
    exec_.finish_small(view(), faces_, n_, out);
    // (Words past the list, when there are faults or fewer vertices, are read and not used.)
    std::vector<u32> got(at + faces_ / 2 + 2);
    exec_.download(got.data(), out, got.size());
    const u32 vertices = got[1];
    faults = got[0] == 0 || checked ? 0 : defects();
    if (faults != 0) return std::nullopt;
    if (at + vertices > got.size()) {
      const std::size_t had = got.size();
      got.resize(at + vertices);
      exec_.download(got.data() + had, out + had, got.size() - had);
    }
    return result_mesh(got.data() + 2, vertices, out + at);
  }

  // The result from what the finish read back: the renumbered corners (3 a face), then `vertices` vertex
  // ids; the coordinates from the host copy, or gathered from the vertex list at `list` where it is.
  BasicHullMesh<Point> result_mesh(const u32* corners_then_vertices, std::size_t vertices, const u32* list) {
    const std::size_t corners = 3 * faces_;
    BasicHullMesh<Point> out;
    out.vertex_ids.assign(corners_then_vertices + corners, corners_then_vertices + corners + vertices);
    resize_populated(out.triangles, faces_);
    static_assert(sizeof(Triangle) == 3 * sizeof(u32));
    std::copy(corners_then_vertices, corners_then_vertices + corners,
              reinterpret_cast<u32*>(out.triangles.data()));
    out.vertices = vertex_coordinates(out.vertex_ids, list);
    return out;
  }

  // The result's coordinates: from the host copy (on all cores), or gathered from the vertex list where it
  // is.
  std::vector<Point> vertex_coordinates(const std::vector<PointIndex>& ids, const u32* list) {
    std::vector<Point> out;
    resize_populated(out, ids.size());
    if (!host_) {
      gather(list, out);
      return out;
    }
    const std::vector<Point>& host = *host_;
    parallel_chunks(
        ids.size(), hardware_workers(),
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t k = begin; k < end; ++k)
            out[k] = host[ids[k]];
        },
        std::size_t{1} << 16);
    return out;
  }

  // With edges that are not strictly convex: the concave edges and the thin vertices (CountConcave,
  // CountThin).  None: the others are flat edges inside coplanar facets, and the mesh is the exact hull.
  // The creases and the vertex flags stay in keep_ and point_rank_, and the concave edges' faces are
  // stamped in revisit_ (free at the finish), for repair_faults().
  u32 defects() {
    const std::size_t n = n_;
    keep_.grow(n);
    point_rank_.grow(n);
    exec_.fill(keep_.data(), n, u32{0});
    exec_.fill(point_rank_.data(), n, u32{0});
    RoundsState* st = state_.data();
    exec_.fill(&st->defects, 1, u32{0});
    exec_.fill(revisit_.data(), faces_, u32{0});
    exec_.for_each(
        faces_, CountConcave<Point>{view(), keep_.data(), point_rank_.data(), &st->defects, revisit_.data()});
    exec_.for_each(n, CountThin{keep_.data(), point_rank_.data(), &st->defects});
    u32 count = 0;
    exec_.download(&count, &st->defects, 1);
    return count;
  }

  // The defects repaired where they are (fault_repair.hpp): the faces within `rings` of one stamped and
  // read back with the ring around them, the host's plan written, the slots left over filled by the last
  // faces.  Returns the patches repaired; `checked`: every patch was, and the new faces passed
  // CheckRepaired (the finish need not count again); the patches' vertices are added to `vertices`.
  // Nothing (no repair, and none worth trying with more rings) when the patches would hold more than
  // kMaxRepairFaces faces or more than half the mesh: flat input (a cylinder's sides, a lattice), whose
  // facets are wider than any patch.  Their plan would take the exact hulls of about as many vertices as
  // the exact finish takes once, so the exact finish answers at once.
  static constexpr std::size_t kMaxRepairFaces = std::size_t{1} << 16;
  std::optional<std::size_t> repair_faults(u32 rings, bool& checked, std::uint64_t& vertices) {
    checked = false;
    // The rings in revisit_ (defects() stamped the concave edges' faces), the stamped faces listed.
    exec_.for_each(
        faces_, FaultRing{CountThin{keep_.data(), point_rank_.data(), nullptr}, fv_.data(), revisit_.data()});
    for (u32 ring = 1; ring <= rings; ++ring)
      exec_.for_each(faces_, SpreadStamp{fn_.data(), revisit_.data(), ring});
    exec_.for_each(faces_, Stamped{revisit_.data(), flags_.data()});
    work_list_.grow(faces_);
    const u32 stamped = exec_.select(flags_.data(), face_rank_.data(), work_list_.data(), faces_);
    if (stamped > kMaxRepairFaces || 2 * std::size_t{stamped} > faces_) return std::nullopt;
    const std::vector<FaceRow> rows = face_rows(work_list_.data(), stamped);
    RepairPlan plan =
        plan_repair<Point>(rows, rings, c_, [&](const std::vector<PointIndex>& ids) { return fetch(ids); });
    vertices += plan.vertices;
    if (plan.patches == 0) return 0;
    write_rows(plan.writes);
    fill_holes(plan.holes, plan.repaired);
    if (plan.patches_left == 0) {
      RoundsState* st = state_.data();
      exec_.fill(&st->defects, 1, u32{0});
      exec_.for_each(plan.repaired.size(), CheckRepaired<Point>{view(), listed(plan.repaired), &st->defects});
      u32 left = 0;
      exec_.download(&left, &st->defects, 1);
      checked = left == 0;
    }
    return plan.patches;
  }

  // The rows of the `count` faces listed at `ids` where the executor computes (their rings from revisit_).
  std::vector<FaceRow> face_rows(const u32* ids, std::size_t count) {
    std::vector<FaceRow> rows(count);
    repair_rows_.grow(count);
    exec_.for_each(count, GatherRows{ids, fv_.data(), fn_.data(), revisit_.data(), repair_rows_.data()});
    exec_.download(rows.data(), repair_rows_.data(), count);
    return rows;
  }
  std::vector<FaceRow> face_rows(const std::vector<u32>& ids) { return face_rows(listed(ids), ids.size()); }
  void write_rows(const std::vector<FaceRow>& rows) {
    repair_rows_.grow(rows.size());
    exec_.upload(repair_rows_.data(), rows.data(), rows.size());
    exec_.for_each(rows.size(), WriteRows{repair_rows_.data(), fv_.data(), fn_.data(), replaced_by_.data()});
  }

  // The slots a repair left over (`holes`, ascending) filled by the mesh's last faces, their neighbours
  // relinked, so that the faces are 0..F-1 again; `renumber` (face ids) follows the moves.
  void fill_holes(const std::vector<u32>& holes, std::vector<u32>& renumber) {
    const std::size_t live = faces_ - holes.size();
    std::vector<u32> movers, targets;
    for (std::size_t f = live; f < faces_; ++f) {
      if (!std::binary_search(holes.begin(), holes.end(), static_cast<u32>(f)))
        movers.push_back(static_cast<u32>(f));
    }
    for (const u32 h : holes) {
      if (h < live) targets.push_back(h);
    }
    faces_ = live;
    if (movers.empty()) return;
    std::unordered_map<u32, u32> to;
    for (std::size_t k = 0; k < movers.size(); ++k)
      to.emplace(movers[k], targets[k]);
    auto moved = [&](u32& f) {
      const auto it = to.find(f);
      if (it != to.end()) f = it->second;
    };
    std::vector<FaceRow> rows = face_rows(movers);
    std::vector<u32> around;
    for (const FaceRow& row : rows) {
      for (const u32 nb : row.n) {
        if (!to.count(nb)) around.push_back(nb);
      }
    }
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    for (std::size_t k = 0; k < rows.size(); ++k)
      rows[k].id = targets[k];
    for (const FaceRow& row : face_rows(around))
      rows.push_back(row);
    for (FaceRow& row : rows) {
      for (u32& nb : row.n)
        moved(nb);
    }
    write_rows(rows);
    for (u32& f : renumber)
      moved(f);
  }

  // The exact reference hull of the mesh's vertices and the points still outside (see the design).
  BasicHullMesh<Point> exact_finish(ResidentStats& stats, const std::string& why) {
    stats.note = why;
    stats.exact_finish = true;
    std::vector<PointIndex> candidates = corners();
    const std::size_t mesh_part = candidates.size();
    candidates.resize(mesh_part + active_);
    exec_.download(candidates.data() + mesh_part, index_[0].data(), active_);
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    return hull_of(candidates, host_ ? std::vector<Point>{} : fetch(candidates));
  }
};

}  // namespace cudahull::resident
