#include "phases/swaps.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <memory>

#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "phases/swap_scratch.hpp"
#include "phases/vector_math.hpp"

namespace cudahull::phases {

bool in_cone_from(const Vec3d& c, const Vec3d& a, const Vec3d& b, const Vec3d& d, const Vec3d& x) {
  const int s = orient3d(c, a, b, d);
  if (s == 0) return false;
  return orient3d(c, a, b, x) * s >= 0 && orient3d(c, b, d, x) * s >= 0 && orient3d(c, d, a, x) * s >= 0;
}

Vec3d far_below(const Vec3d& at, const Vec3d& up, double size) {
  const double reach = 1e3 * size;
  return {at.x - reach * up.x, at.y - reach * up.y, at.z - reach * up.z};
}

double extent(std::initializer_list<Vec3d> points) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const Vec3d& p : points) {
    lo[0] = std::min(lo[0], p.x), hi[0] = std::max(hi[0], p.x);
    lo[1] = std::min(lo[1], p.y), hi[1] = std::max(hi[1], p.y);
    lo[2] = std::min(lo[2], p.z), hi[2] = std::max(hi[2], p.z);
  }
  return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
}

namespace {

// Is x in the closed tetrahedron (c, a, b, d)?  Then x is inside the hull of the input and not extreme.
bool proven_inside(const Vec3d& c, const Vec3d& a, const Vec3d& b, const Vec3d& d, const Vec3d& x) {
  const int s = orient3d(a, b, d, c);
  if (s == 0) return false;
  return orient3d(a, b, d, x) * s >= 0 && in_cone_from(c, a, b, d, x);
}

// A swap's four vertices (u, v, x, y), and the four outer edges of its new faces n1, n2: what it touches
// and queues.
std::array<PointIndex, 4> vertices_of(const SwapRecord& swap) {
  return {swap.old_edge[0], swap.old_edge[1], swap.new_edge[0], swap.new_edge[1]};
}
std::array<Edge, 4> edges_around(FaceId n1, FaceId n2) {
  return {{{n1, 0}, {n1, 1}, {n2, 0}, {n2, 1}}};
}

// What try_swap() would do with edge i of face f, changing nothing (so the rounds can ask on many threads
// at once): the outcome, the swap's edges, and for a rejection the verdict and whether the vertex beneath
// is proven inside the hull.
template <class Point>
SwapTrial trial_swap(const LocalEdits<Point>& edits, FaceId f, int i, const Vec3d* around_doomed) {
  SwapTrial t;
  const Mesh& mesh = edits.mesh;
  const MeshFace& face = mesh.face(f);
  const PointIndex u = face.v[i], v = face.v[(i + 1) % 3], x = face.v[(i + 2) % 3];
  const FaceId g = face.n[i];
  t.other_face = g;
  if (g == kNoFace || g >= mesh.face_capacity() || !mesh.alive(g)) return t;
  const int j = mesh.edge_index(g, v, u);
  if (j < 0) return t;
  const PointIndex y = mesh.face(g).v[(j + 2) % 3];
  if (!around_doomed) {
    if (orient3d(edits.P(u), edits.P(v), edits.P(x), edits.P(y)) <= 0) return t;  // convex or flat
    // Never give a vertex that is being taken out a new edge; its removal re-queues this edge.
    if (edits.is_doomed(x) || edits.is_doomed(y)) return t;
  }
  SwapRecord& swap = t.swap;
  swap.old_edge[0] = u;
  swap.old_edge[1] = v;
  swap.new_edge[0] = x;
  swap.new_edge[1] = y;
  t.verdict = swap_validity(edits, u, v, x, y, swap, around_doomed);
  if (t.verdict == SwapKind::kRegular) {
    t.outcome = SwapTrial::kValid;
    return t;
  }
  if (around_doomed) return t;
  t.beneath_inside =
      swap.beneath_vertex != kNoPoint &&
      proven_inside(edits.interior, edits.P(swap.beneath_triangle[0]), edits.P(swap.beneath_triangle[1]),
                    edits.P(swap.beneath_triangle[2]), edits.P(swap.beneath_vertex));
  t.outcome = SwapTrial::kRejected;
  return t;
}

// A rejection's effect on the edits; true when it is to be recorded.
template <class Point>
bool doom_and_mark_rejected(LocalEdits<Point>& edits, const SwapRecord& swap, bool beneath_inside) {
  // A vertex beneath that is inside the hull is taken out with complementary swaps and a removal (Fig. 4).
  if (beneath_inside && !edits.is_doomed(swap.beneath_vertex)) {
    edits.vertex_flags[swap.beneath_vertex] |= kDoomed;
    ++edits.doomed_now;
    edits.doomed.push_back(swap.beneath_vertex);
  }
  // Record each rejected edge once per iteration, however often a neighbour change re-queues it.
  const PointIndex u = swap.old_edge[0], v = swap.old_edge[1];
  return edits.rejected_edges.insert({std::min(u, v), std::max(u, v)}).second;
}

// Makes a batch of valid swaps that kill pairwise different faces and make pairwise different edges
// (made[w] = face and edge of winner w): the mesh edit, then per winner its decision entry and its record
// in record.swaps[first_record + slot(w)] with sequence first_sequence + slot(w).  `winner` maps w to its
// trial.  Returns the first new face id: winner w made faces first + 2w and first + 2w + 1.
template <class Point, class Winner, class Slot>
FaceId make_swaps(LocalEdits<Point>& edits, const std::vector<std::pair<FaceId, int>>& made, Winner&& winner,
                  Slot&& slot, std::size_t first_record, int first_sequence) {
  const std::size_t count = made.size();
  // One swap (the one-at-a-time path, hundreds an iteration on a cube) takes the mesh's single edit: the
  // same faces and links as a batch of one, without the batch's buffers, which cost a measurable share of
  // the host's instructions on a cube (docs/benchmarks.md, "Measurements behind the code").
  const FaceId first = count == 1 ? edits.mesh.swap(made[0].first, made[0].second)[0]
                                  : edits.mesh.swap_batch(made, hardware_workers());
  const std::int32_t first_entry = edits.decisions.add_swap_slots(count, edits.mesh.face_capacity());
  auto make_one = [&](std::size_t w) {
    SwapTrial& t = winner(w);
    const FaceId n1 = first + 2 * static_cast<FaceId>(w), n2 = n1 + 1;
    const std::size_t at = slot(w);
    const auto entry = first_entry + static_cast<std::int32_t>(w);
    edits.decisions.write_swap(entry, made[w].first, t.other_face, n1, n2, t.swap.old_edge[0]);
    t.swap.decision_index = entry;
    t.swap.sequence = first_sequence + static_cast<int>(at);
    edits.record.swaps[first_record + at] = t.swap;
  };
  if (count == 1) {
    make_one(0);
  } else {
    parallel_chunks(
        count, hardware_workers(),
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t w = begin; w < end; ++w)
            make_one(w);
        },
        4096);
  }
  return first;
}

void count_made(IterationRecord& record, SwapKind kind, std::size_t count) {
  (kind == SwapKind::kRegular ? record.swaps_regular : record.swaps_complementary) += count;
}

}  // namespace

template <class Point>
SwapKind swap_validity(const LocalEdits<Point>& edits, PointIndex u, PointIndex v, PointIndex x, PointIndex y,
                       SwapRecord& swap, const Vec3d* view) {
  if (edits.mesh.adjacent(x, y)) return SwapKind::kRejectedEdgeExists;
  const Vec3d pu = edits.P(u), pv = edits.P(v), px = edits.P(x), py = edits.P(y);
  const Vec3d n =
      add(normalized(cross(sub(pv, pu), sub(px, pu))), normalized(cross(sub(pu, pv), sub(py, pv))));
  const Vec3d mid{(pu.x + pv.x) / 2, (pu.y + pv.y) / 2, (pu.z + pv.z) / 2};
  const Vec3d c = view ? *view : far_below(mid, normalized(n), extent({pu, pv, px, py}));
  const int su = orient3d(c, px, py, pu), sv = orient3d(c, px, py, pv);
  const int sx = orient3d(c, pu, pv, px), sy = orient3d(c, pu, pv, py);
  if (su == 0 || sv == 0 || sx == 0 || sy == 0) return SwapKind::kRejectedDegenerate;
  if (su != sv && sx != sy) return SwapKind::kRegular;  // valid
  if (in_cone_from(c, py, pv, px, pu)) {
    swap.beneath_vertex = u;
    swap.beneath_triangle[0] = y, swap.beneath_triangle[1] = v, swap.beneath_triangle[2] = x;
  } else if (in_cone_from(c, px, pu, py, pv)) {
    swap.beneath_vertex = v;
    swap.beneath_triangle[0] = x, swap.beneath_triangle[1] = u, swap.beneath_triangle[2] = y;
  }
  return SwapKind::kRejectedFoldover;
}

template <class Point>
bool try_swap(LocalEdits<Point>& edits, FaceId f, int i, SwapKind kind, const Vec3d* around_doomed) {
  SwapTrial t = trial_swap(edits, f, i, around_doomed);
  IterationRecord& record = edits.record;
  if (t.outcome == SwapTrial::kRejected && doom_and_mark_rejected(edits, t.swap, t.beneath_inside)) {
    t.swap.kind = t.verdict;
    t.swap.sequence = edits.sequence++;
    record.swaps.push_back(t.swap);
    ++record.swaps_rejected;
  }
  if (t.outcome != SwapTrial::kValid) return false;
  // A batch of one.
  const std::size_t first_record = record.swaps.size();
  record.swaps.emplace_back();
  t.swap.kind = kind;
  edits.scratch.single.assign(1, {f, i});
  const FaceId n1 = make_swaps(
      edits, edits.scratch.single, [&](std::size_t) -> SwapTrial& { return t; },
      [](std::size_t) { return 0; }, first_record, edits.sequence++);
  count_made(record, kind, 1);
  for (const Edge& edge : edges_around(n1, n1 + 1))
    edits.queue.push_back(edge);
  for (PointIndex p : vertices_of(t.swap))
    edits.touch(p);
  return true;
}

template <class Point>
void swap_edges(LocalEdits<Point>& edits, std::vector<SwapCandidate> candidates) {
  const unsigned workers = hardware_workers();
  SwapScratch& scratch = edits.scratch;
  IterationRecord& record = edits.record;
  Mesh& mesh = edits.mesh;
  std::vector<SwapTrial>& trials = scratch.trials;
  std::vector<SwapCandidate> next;
  double t_eval = 0, t_claim = 0, t_apply = 0, t_book = 0;  // CUDAHULL_PHASE_TIMES
  int rounds = 0;
  while (candidates.size() >= edits.batched_swaps_from && edits.budget > 0) {
    auto q0 = Clock::now();
    ++rounds;
    const std::size_t count = candidates.size();
    // 1. Every candidate tried at once, the mesh unchanged.
    trials.resize(count);
    parallel_chunks(
        count, workers,
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t k = begin; k < end; ++k) {
            const Edge& edge = candidates[k].edge;
            trials[k] =
                mesh.alive(edge.face) ? trial_swap(edits, edge.face, edge.index, nullptr) : SwapTrial{};
          }
        },
        256);
    t_eval += ms_since(q0);
    q0 = Clock::now();
    // 2. Claims, tagged by round so that the tables need no clearing and stay from one iteration to the
    // next: a swap wins when it is the lowest candidate among those that would kill either of its two faces
    // and among those that would make its new edge (hashed; a collision only delays a swap to the next
    // round).
    scratch.grow_claims(mesh.face_capacity(), 4 * count);
    const std::uint64_t round = ++scratch.claim_round;
    auto claim = [round](std::atomic_ref<std::uint64_t> slot, std::uint64_t k) {
      const std::uint64_t mine = round << 32 | k;
      std::uint64_t held = slot.load(std::memory_order_relaxed);
      while ((held >> 32 != round || held > mine) &&
             !slot.compare_exchange_weak(held, mine, std::memory_order_relaxed)) {
      }
    };
    parallel_chunks(
        count, workers,
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t k = begin; k < end; ++k) {
            const SwapTrial& t = trials[k];
            if (t.outcome != SwapTrial::kValid) continue;
            claim(scratch.face_claim(candidates[k].edge.face), k);
            claim(scratch.face_claim(t.other_face), k);
            claim(scratch.edge_claim(t.swap.new_edge[0], t.swap.new_edge[1]), k);
          }
        },
        256);
    parallel_chunks(
        count, workers,
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t k = begin; k < end; ++k) {
            SwapTrial& t = trials[k];
            if (t.outcome != SwapTrial::kValid) continue;
            const std::uint64_t mine = round << 32 | k;
            t.winner =
                scratch.face_claim(candidates[k].edge.face).load(std::memory_order_relaxed) == mine &&
                scratch.face_claim(t.other_face).load(std::memory_order_relaxed) == mine &&
                scratch.edge_claim(t.swap.new_edge[0], t.swap.new_edge[1]).load(std::memory_order_relaxed) ==
                    mine;
          }
        },
        256);
    // 3. The outcomes numbered in candidate order, as one at a time would number them, but on all cores:
    // per block of candidates the count of winners, losers (valid, but an earlier candidate took a face or
    // the new edge: tried again next round) and rejections; then each block's offsets; then the numbering.
    const SwapScratch::BlockCount total = scratch.number_outcomes(candidates, workers);
    const std::size_t winners = total.winners;
    if (winners == 0) break;
    next.resize(total.losers + 4 * winners);
    scratch.collect(candidates, next, workers);
    t_claim += ms_since(q0);
    q0 = Clock::now();
    edits.budget = edits.budget > winners ? edits.budget - winners : 0;
    // 4. Rejections in order (they doom vertices, and each edge is recorded once an iteration; they are
    // few).  Records and sequence numbers follow candidate order, winners and recorded rejections
    // interleaved.
    const std::size_t first_record = record.swaps.size();
    const int first_sequence = edits.sequence;
    std::vector<std::size_t>& recorded = scratch.recorded;  // candidates of the recorded rejections
    recorded.clear();
    for (std::size_t r = 0; r < scratch.rejected_at.size(); ++r) {
      SwapTrial& t = trials[scratch.rejected_at[r]];
      if (!doom_and_mark_rejected(edits, t.swap, t.beneath_inside)) continue;
      const std::size_t slot = scratch.wins_before[r] + recorded.size();
      t.swap.kind = t.verdict;
      t.swap.sequence = first_sequence + static_cast<int>(slot);
      if (record.swaps.size() < first_record + slot + 1) record.swaps.resize(first_record + slot + 1);
      record.swaps[first_record + slot] = t.swap;
      ++record.swaps_rejected;
      recorded.push_back(scratch.rejected_at[r]);
    }
    record.swaps.resize(first_record + winners + recorded.size());
    edits.sequence = first_sequence + static_cast<int>(winners + recorded.size());
    record.swaps_regular += total.regular;
    record.swaps_complementary += winners - total.regular;
    // 5. The winners made together; each winner's slot comes after the winners and the recorded
    // rejections before it.
    const std::vector<std::size_t>& of = scratch.candidate_of;  // winner -> candidate
    const FaceId first = make_swaps(
        edits, scratch.made,
        [&](std::size_t w) -> SwapTrial& {
          trials[of[w]].swap.kind = candidates[of[w]].kind;
          return trials[of[w]];
        },
        [&](std::size_t w) {
          return w + static_cast<std::size_t>(std::lower_bound(recorded.begin(), recorded.end(), of[w]) -
                                              recorded.begin());
        },
        first_record, first_sequence);
    t_apply += ms_since(q0);
    q0 = Clock::now();
    // 6. The edges around the swaps made are the next round's complementary candidates, and their vertices
    // are touched (settle() dedupes them).
    const std::size_t carried = total.losers, first_touch = edits.touched.size();
    edits.touched.resize(first_touch + 4 * winners);
    parallel_chunks(
        winners, workers,
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t w = begin; w < end; ++w) {
            const FaceId n1 = first + 2 * static_cast<FaceId>(w);
            SwapCandidate* around = next.data() + carried + 4 * w;
            for (const Edge& edge : edges_around(n1, n1 + 1))
              *around++ = {edge, SwapKind::kComplementary};
            const std::array<PointIndex, 4> vertices = vertices_of(trials[of[w]].swap);
            std::copy(vertices.begin(), vertices.end(), edits.touched.begin() + first_touch + 4 * w);
          }
        },
        4096);
    edits.touched_unsorted = true;
    candidates.swap(next);
    t_book += ms_since(q0);
  }
  if (phase_times_wanted() && rounds > 0)
    std::fprintf(stderr, "  batched swaps: %d rounds, try %.1f claim %.1f swap %.1f bookkeeping %.1f ms\n",
                 rounds, t_eval, t_claim, t_apply, t_book);
  // What is left goes on as one at a time: regular candidates now, as in the unbatched order.
  for (const SwapCandidate& c : candidates) {
    if (c.kind != SwapKind::kRegular) {
      edits.queue.push_back(c.edge);
    } else if (mesh.alive(c.edge.face)) {
      try_swap(edits, c.edge.face, c.edge.index, SwapKind::kRegular);
    }
  }
}

// The two coordinate types (README, "Precision").
template SwapKind swap_validity(const LocalEdits<Point3>&, PointIndex, PointIndex, PointIndex, PointIndex,
                                SwapRecord&, const Vec3d*);
template bool try_swap(LocalEdits<Point3>&, FaceId, int, SwapKind, const Vec3d*);
template void swap_edges(LocalEdits<Point3>&, std::vector<SwapCandidate>);
template SwapKind swap_validity(const LocalEdits<Point3d>&, PointIndex, PointIndex, PointIndex, PointIndex,
                                SwapRecord&, const Vec3d*);
template bool try_swap(LocalEdits<Point3d>&, FaceId, int, SwapKind, const Vec3d*);
template void swap_edges(LocalEdits<Point3d>&, std::vector<SwapCandidate>);

}  // namespace cudahull::phases
