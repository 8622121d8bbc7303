#include "cudahull/engine.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <memory>
#include <set>
#include <stdexcept>
#include <unordered_set>

#include "cudahull/exact_hull.hpp"
#include "cudahull/parallel.hpp"
#include "cudahull/phase_times.hpp"
#include "cudahull/predicates.hpp"

namespace cudahull {

const char* swap_kind_name(SwapKind kind) {
  switch (kind) {
    case SwapKind::kRegular:
      return "regular";
    case SwapKind::kComplementary:
      return "complementary";
    case SwapKind::kRejectedFoldover:
      return "rejected_foldover";
    case SwapKind::kRejectedEdgeExists:
      return "rejected_edge_exists";
    case SwapKind::kRejectedDegenerate:
      return "rejected_degenerate";
  }
  return "unknown";
}

namespace {

Vec3d sub(const Vec3d& a, const Vec3d& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Vec3d add(const Vec3d& a, const Vec3d& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(const Vec3d& a, const Vec3d& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
Vec3d normalized(const Vec3d& a) {
  // Scale first so that huge or tiny coordinates (1e30, 1e-30) neither overflow nor underflow.
  const double m = std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)});
  if (m == 0) return {0, 0, 0};
  const double inverse = 1 / m;  // two divisions in all instead of six: this runs ~10 times a refinement
  const Vec3d s{a.x * inverse, a.y * inverse, a.z * inverse};
  const double k = 1 / std::sqrt(dot(s, s));
  return {s.x * k, s.y * k, s.z * k};
}

// The plane through a and b that contains direction `along`, positive on the side of `inside`.
SeparatingPlane plane_through_edge(const Vec3d& a, const Vec3d& b, const Vec3d& along, const Vec3d& inside) {
  Vec3d m = normalized(cross(normalized(sub(b, a)), along));
  double d = -dot(m, a);
  if (dot(m, inside) + d < 0) {
    m = {-m.x, -m.y, -m.z};
    d = -d;
  }
  return {m.x, m.y, m.z, d};
}

struct Edge {
  FaceId face;
  int index;
};

// Per-point flags of the mesh edits.
constexpr std::uint8_t kDoomed = 1;       // a vertex proven inside the hull, being taken out
constexpr std::uint8_t kRemovedOnce = 2;  // removed as concave before: a fold made it look concave
constexpr std::uint8_t kTouched = 4;      // queued as a removal candidate
constexpr int kStallLimit = 8;            // iterations without fewer external points before finishing

}  // namespace

namespace {
// A swap tried without changing the mesh (Engine::Impl::trial_swap) and the batched rounds' view of it.
enum class SwapTrial : std::uint8_t { kNothing, kValid, kRejected };
struct SwapCandidate {
  Edge edge;
  SwapKind kind;
};
struct BatchTrial {
  SwapTrial trial = SwapTrial::kNothing;
  SwapKind verdict = SwapKind::kRegular;
  bool beneath_inside = false;
  bool winner = false;
  FaceId other_face = kNoFace;  // g, the face across the edge
  SwapRecord swap;
};
}  // namespace

// Per block of kNumberingBlock candidates of a batched round: how many won, lost, were rejected, and won
// as regular swaps; then, after a prefix sum, the same counts before the block.
struct BlockCount {
  std::size_t winners = 0, losers = 0, rejected = 0, regular = 0;
};
using BlockCounts = std::vector<BlockCount>;
constexpr std::size_t kNumberingBlock = 4096;

// Buffers of the batched swap rounds, kept from one iteration to the next (fresh arrays of this size would
// cost page faults every time).
struct Engine::EditScratch {
  std::vector<BatchTrial> trials;            // per candidate
  std::vector<std::pair<FaceId, int>> made;  // the round's winners: face and edge
  std::vector<std::size_t> winner_of, rejected_at, wins_before, recorded;
  BlockCounts counts;
  // Claims, (round << 32 | candidate): per face id, and per hashed new edge (used through atomic_ref).
  std::unique_ptr<std::uint64_t[]> face_claims, edge_claims;
  std::size_t face_claim_count = 0, edge_claim_bits = 0;
  std::uint64_t claim_round = 0;

  // Grown tables are zeroed on all cores: a serial clear of 100 MB would cost more than a round.
  static void zero(std::uint64_t* table, std::size_t count) {
    parallel_chunks(count, hardware_workers(), [&](std::size_t begin, std::size_t end, unsigned) {
      std::fill(table + begin, table + end, std::uint64_t{0});
    });
  }
  void grow_claims(std::size_t faces, std::size_t edges) {
    if (faces > face_claim_count) {
      face_claim_count = std::max(faces, face_claim_count + face_claim_count / 2);
      face_claims.reset(new std::uint64_t[face_claim_count]);
      zero(face_claims.get(), face_claim_count);
    }
    std::size_t bits = 12;
    while ((std::size_t{1} << bits) < 2 * edges)
      ++bits;
    if (bits > edge_claim_bits) {
      edge_claims.reset(new std::uint64_t[std::size_t{1} << bits]);
      zero(edge_claims.get(), std::size_t{1} << bits);
      edge_claim_bits = bits;
    }
  }
  std::atomic_ref<std::uint64_t> face_claim(FaceId f) {
    return std::atomic_ref<std::uint64_t>(face_claims[f]);
  }
  std::atomic_ref<std::uint64_t> edge_claim(PointIndex a, PointIndex b) {
    const std::uint64_t key = static_cast<std::uint64_t>(std::min(a, b)) << 32 | std::max(a, b);
    return std::atomic_ref<std::uint64_t>(
        edge_claims[(key * 0x9E3779B97F4A7C15ull) >> (64 - edge_claim_bits)]);
  }
};

struct Engine::Impl {
  // One iteration's mesh edits (Algorithm 1) and their decision entries, in work ids (face ids before
  // compaction).  Entries target work ids; they become route codes once the new ids are known.
  Engine& e;
  IterationRecord& record;
  std::vector<DecisionEntry> entries;
  std::vector<std::array<FaceId, 2>> entry_targets;  // work ids: above, below
  std::vector<std::int32_t> killed_by_entry;         // work id -> decision entry, or -1
  std::deque<Edge> queue;
  std::vector<PointIndex> touched;  // vertices whose neighbourhood changed: removal candidates
  // Batched edits append to `touched` on all cores without the kTouched flag, repeats and all; settle()
  // then sorts and dedupes it (an order that does not depend on the number of threads).
  bool touched_unsorted = false;
  std::vector<PointIndex> doomed;  // vertices proven not extreme, to be taken out (Fig. 4)
  std::set<std::pair<PointIndex, PointIndex>> rejected_edges;
  // Swap entries whose separating plane is still to compute: the new faces (x, u, y) and (y, v, x) and u.
  struct PendingPlane {
    std::int32_t entry;
    FaceId n1, n2;
    PointIndex u;
  };
  std::vector<PendingPlane> swap_planes;
  std::vector<PointIndex> ring;    // scratch
  std::vector<FaceId> ring_faces;  // scratch
  int sequence = 0;
  // Edits left before settle() gives up (a guard against cycling on degenerate input; the exact finish
  // repairs what is left).  Every swap counts, those of take_out() included.
  std::size_t budget = 0;

  explicit Impl(Engine& engine, IterationRecord& r) : e(engine), record(r) {}

  Vec3d P(PointIndex i) const { return to_vec3d(e.points_[i]); }
  Vec3d unit_normal(FaceId f) const {
    const MeshFace& face = e.mesh_.face(f);
    return normalized(cross(sub(P(face.v[1]), P(face.v[0])), sub(P(face.v[2]), P(face.v[0]))));
  }
  // Most iterations doom no vertex: then no lookup (two per tried swap) is needed.
  std::size_t doomed_now = 0;
  bool is_doomed(PointIndex v) const { return doomed_now != 0 && (e.vertex_flags_.get(v) & kDoomed) != 0; }
  // Queues v once as a removal candidate.
  void touch(PointIndex v) {
    std::uint8_t& flags = e.vertex_flags_[v];
    if (flags & kTouched) return;
    flags |= kTouched;
    touched.push_back(v);
  }

  void note_killed(FaceId f, std::int32_t entry) {
    if (killed_by_entry.size() <= f) killed_by_entry.resize(f + 1, -1);
    killed_by_entry[f] = entry;
  }

  std::int32_t add_entry(const DecisionEntry& entry, FaceId above, FaceId below) {
    entries.push_back(entry);
    entry_targets.push_back({above, below});
    return static_cast<std::int32_t>(entries.size() - 1);
  }

  // Is x inside the cone from viewpoint c over triangle (a, b, d)?  Exact.
  static bool in_cone_from(const Vec3d& c, const Vec3d& a, const Vec3d& b, const Vec3d& d, const Vec3d& x) {
    const int s = orient3d(c, a, b, d);
    if (s == 0) return false;
    return orient3d(c, a, b, x) * s >= 0 && orient3d(c, b, d, x) * s >= 0 && orient3d(c, d, a, x) * s >= 0;
  }

  // Is x in the closed tetrahedron (c, a, b, d)?  Then x is inside the hull of the input and not extreme.
  bool proven_inside(const Vec3d& a, const Vec3d& b, const Vec3d& d, const Vec3d& x) const {
    const int s = orient3d(a, b, d, e.interior_);
    if (s == 0) return false;
    return orient3d(a, b, d, x) * s >= 0 && in_cone_from(e.interior_, a, b, d, x);
  }

  // The swap of edge u - v (faces (u, v, x) and (v, u, y)) is valid when, in the central projection from
  // the interior point c (where the hull is a sphere), the old and the new edge cross: u, v on opposite sides
  // of the plane (c, x, y) and x, y on opposite sides of (c, u, v).  Otherwise a vertex of the old edge lies
  // beneath a new triangle: a foldover (Fig. 5).
  // The viewpoint far below `at` along direction `up` (scaled to `size`): seen from there, orientation tests
  // are the parallel projection along `up` (the height-field view of Fig. 5), yet still exact predicates.
  static Vec3d far_below(const Vec3d& at, const Vec3d& up, double size) {
    const double reach = 1e3 * size;
    return {at.x - reach * up.x, at.y - reach * up.y, at.z - reach * up.z};
  }
  static double extent(std::initializer_list<Vec3d> points) {
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (const Vec3d& p : points) {
      lo[0] = std::min(lo[0], p.x), hi[0] = std::max(hi[0], p.x);
      lo[1] = std::min(lo[1], p.y), hi[1] = std::max(hi[1], p.y);
      lo[2] = std::min(lo[2], p.z), hi[2] = std::max(hi[2], p.z);
    }
    return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  }

  // The view is from far below the edge along the average normal of its two faces, or `view` when given
  // (one common viewpoint for the swaps around a vertex being taken out).
  SwapKind swap_validity(PointIndex u, PointIndex v, PointIndex x, PointIndex y, SwapRecord& swap,
                         const Vec3d* view = nullptr) const {
    if (e.mesh_.adjacent(x, y)) return SwapKind::kRejectedEdgeExists;
    const Vec3d pu = P(u), pv = P(v), px = P(x), py = P(y);
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

  // What try_swap() would do with edge i of face f, changing nothing (so the batched rounds can ask on many
  // threads at once).  Fills `swap` (edges; for a foldover the vertex beneath) and, for a rejection,
  // `verdict` and whether the vertex beneath is proven inside the hull.
  using Trial = SwapTrial;
  Trial trial_swap(FaceId f, int i, const Vec3d* around_doomed, SwapRecord& swap, SwapKind& verdict,
                   bool& beneath_inside) const {
    const MeshFace& face = e.mesh_.face(f);
    const PointIndex u = face.v[i], v = face.v[(i + 1) % 3], x = face.v[(i + 2) % 3];
    const FaceId g = face.n[i];
    if (g == kNoFace || g >= e.mesh_.face_capacity() || !e.mesh_.alive(g)) return Trial::kNothing;
    const int j = e.mesh_.edge_index(g, v, u);
    if (j < 0) return Trial::kNothing;
    const PointIndex y = e.mesh_.face(g).v[(j + 2) % 3];
    if (!around_doomed) {
      if (orient3d(P(u), P(v), P(x), P(y)) <= 0) return Trial::kNothing;  // convex or flat: nothing to do
      // Never give a vertex that is being taken out a new edge; its removal re-queues this edge.
      if (is_doomed(x) || is_doomed(y)) return Trial::kNothing;
    }
    swap.old_edge[0] = u;
    swap.old_edge[1] = v;
    swap.new_edge[0] = x;
    swap.new_edge[1] = y;
    verdict = swap_validity(u, v, x, y, swap, around_doomed);
    if (verdict == SwapKind::kRegular) return Trial::kValid;
    if (around_doomed) return Trial::kNothing;
    // The vertex beneath is inside the hull when it is inside the tetrahedron of c and that triangle.
    beneath_inside = swap.beneath_vertex != kNoPoint &&
                     proven_inside(P(swap.beneath_triangle[0]), P(swap.beneath_triangle[1]),
                                   P(swap.beneath_triangle[2]), P(swap.beneath_vertex));
    return Trial::kRejected;
  }

  // A rejection's effect on the edits; true when it is to be recorded.
  bool doom_and_mark_rejected(const SwapRecord& swap, bool beneath_inside) {
    // A vertex beneath that is inside the hull is taken out with complementary swaps and a removal (Fig. 4).
    if (beneath_inside && !is_doomed(swap.beneath_vertex)) {
      e.vertex_flags_[swap.beneath_vertex] |= kDoomed;
      ++doomed_now;
      doomed.push_back(swap.beneath_vertex);
    }
    // Record each rejected edge once per iteration, however often a neighbour change re-queues it.
    const PointIndex u = swap.old_edge[0], v = swap.old_edge[1];
    return rejected_edges.insert({std::min(u, v), std::max(u, v)}).second;
  }

  void note_rejected(SwapRecord& swap, SwapKind verdict, bool beneath_inside) {
    if (doom_and_mark_rejected(swap, beneath_inside)) {
      swap.kind = verdict;
      swap.sequence = sequence++;
      record.swaps.push_back(swap);
      ++record.swaps_rejected;
    }
  }

  // A swap's four vertices (u, v, x, y), and the four outer edges of its new faces n1, n2: what it touches
  // and queues.
  static std::array<PointIndex, 4> vertices_of(const SwapRecord& swap) {
    return {swap.old_edge[0], swap.old_edge[1], swap.new_edge[0], swap.new_edge[1]};
  }
  static std::array<Edge, 4> edges_around(FaceId n1, FaceId n2) {
    return {{{n1, 0}, {n1, 1}, {n2, 0}, {n2, 1}}};
  }

  // A swap's decision entry, in slots the caller made: entry `index` and pending plane `plane`.  Points of
  // f and g go to n1 (the u side) or n2 (the v side) by the new edge's separating plane, which
  // separating_planes() computes after the edits.  Writes only those slots, so batched swaps fill theirs on
  // all cores.
  void write_swap_entry(std::int32_t index, std::size_t plane, FaceId f, FaceId g, FaceId n1, FaceId n2,
                        SwapRecord& swap) {
    entries[index] = DecisionEntry{};
    entries[index].kind = kDecisionSwap;
    entry_targets[index] = {n1, n2};
    swap_planes[plane] = {index, n1, n2, swap.old_edge[0]};
    killed_by_entry[f] = index;
    killed_by_entry[g] = index;
    swap.decision_index = index;
  }

  // The bookkeeping of a swap made (faces f, g became n1, n2): its decision entry, record, the four edges
  // around it queued, its vertices touched.
  void note_swapped(FaceId f, FaceId g, FaceId n1, FaceId n2, SwapRecord& swap, SwapKind kind) {
    const auto index = static_cast<std::int32_t>(entries.size());
    entries.emplace_back();
    entry_targets.emplace_back();
    swap_planes.emplace_back();
    if (killed_by_entry.size() <= std::max(f, g)) killed_by_entry.resize(std::max(f, g) + 1, -1);
    write_swap_entry(index, swap_planes.size() - 1, f, g, n1, n2, swap);
    swap.kind = kind;
    swap.sequence = sequence++;
    record.swaps.push_back(swap);
    (kind == SwapKind::kRegular ? record.swaps_regular : record.swaps_complementary)++;
    for (const Edge& edge : edges_around(n1, n2))
      queue.push_back(edge);
    for (PointIndex p : vertices_of(swap))
      touch(p);
  }

  // Fig. 3b: swap edge i of face f.  Only concave edges, unless `around_doomed` (a complementary swap that
  // lowers the degree of a vertex being taken out).  Returns true if swapped.
  bool try_swap(FaceId f, int i, SwapKind kind, const Vec3d* around_doomed = nullptr) {
    SwapRecord swap;
    SwapKind verdict = SwapKind::kRegular;
    bool beneath_inside = false;
    const Trial trial = trial_swap(f, i, around_doomed, swap, verdict, beneath_inside);
    if (trial == Trial::kRejected) note_rejected(swap, verdict, beneath_inside);
    if (trial != Trial::kValid) return false;
    const FaceId g = e.mesh_.face(f).n[i];
    const auto [n1, n2] = e.mesh_.swap(f, i);
    note_swapped(f, g, n1, n2, swap, kind);
    return true;
  }

  // Batched swaps, for iterations with thousands of candidate edges (a sphere of 1M points makes 1.5M
  // swaps): rounds of (1) every candidate tried at once on all cores, the mesh unchanged; (2) among the
  // valid swaps, those that are the lowest candidate among all that would kill either of their two faces
  // or make their new edge, so the result does not depend on the number of threads; (3) those swaps made
  // at once (Mesh::swap_batch); (4) the bookkeeping in candidate order, as try_swap() would have done it.
  // Such swaps commute: none kills another's faces or makes another's new edge, and concavity and validity
  // depend only on a swap's own four points, so each is exactly what try_swap() would do at its turn.
  // Candidates that lost go to the next round with the edges the winners queued, until fewer than
  // `batch_from` remain; the rest go one at a time (regular ones now, the others on settle()'s queue).
  using Candidate = SwapCandidate;

  void batched_swaps(std::vector<Candidate> candidates, std::size_t batch_from) {
    const unsigned workers = hardware_workers();
    if (!e.scratch_) e.scratch_ = std::make_unique<EditScratch>();
    EditScratch& scratch = *e.scratch_;
    std::vector<BatchTrial>& trials = scratch.trials;
    std::vector<Candidate> next;
    double t_eval = 0, t_claim = 0, t_apply = 0, t_book = 0;  // CUDAHULL_PHASE_TIMES
    int rounds = 0;
    while (candidates.size() >= batch_from && budget > 0) {
      auto q0 = Clock::now();
      ++rounds;
      const std::size_t count = candidates.size();
      trials.resize(count);
      parallel_chunks(
          count, workers,
          [&](std::size_t begin, std::size_t end, unsigned) {
            for (std::size_t k = begin; k < end; ++k) {
              const Edge& edge = candidates[k].edge;
              BatchTrial& t = trials[k];
              t = BatchTrial{};
              if (!e.mesh_.alive(edge.face)) continue;
              t.trial = trial_swap(edge.face, edge.index, nullptr, t.swap, t.verdict, t.beneath_inside);
              t.other_face = e.mesh_.face(edge.face).n[edge.index];
            }
          },
          256);
      t_eval += ms_since(q0);
      q0 = Clock::now();
      // Claims, tagged by round so that the tables need no clearing and stay from one iteration to the next:
      // a swap wins when it is the lowest candidate among those that would kill either of its two faces and
      // among those that would make its new edge (hashed; a collision only delays a swap to the next round).
      scratch.grow_claims(e.mesh_.face_capacity(), 4 * count);
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
              const BatchTrial& t = trials[k];
              if (t.trial != Trial::kValid) continue;
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
              BatchTrial& t = trials[k];
              if (t.trial != Trial::kValid) continue;
              const std::uint64_t mine = round << 32 | k;
              t.winner =
                  scratch.face_claim(candidates[k].edge.face).load(std::memory_order_relaxed) == mine &&
                  scratch.face_claim(t.other_face).load(std::memory_order_relaxed) == mine &&
                  scratch.edge_claim(t.swap.new_edge[0], t.swap.new_edge[1])
                          .load(std::memory_order_relaxed) == mine;
            }
          },
          256);
      // The outcomes numbered in candidate order, as note_swapped() and note_rejected() one at a time would
      // number them, but on all cores: per block of candidates the count of winners, losers (valid, but an
      // earlier candidate took a face or the new edge: tried again next round) and rejections; then each
      // block's offsets; then the numbering.  Only the rejections go one at a time, in order (they doom
      // vertices, and each edge is recorded once an iteration), and they are few.
      BlockCounts& counts = scratch.counts;
      const std::size_t blocks = (count + kNumberingBlock - 1) / kNumberingBlock;
      counts.resize(blocks);
      parallel_chunks(
          blocks, workers,
          [&](std::size_t begin, std::size_t end, unsigned) {
            for (std::size_t b = begin; b < end; ++b) {
              BlockCount c;
              for (std::size_t k = b * kNumberingBlock; k < std::min(count, (b + 1) * kNumberingBlock); ++k) {
                const BatchTrial& t = trials[k];
                if (t.winner) {
                  ++c.winners;
                  c.regular += candidates[k].kind == SwapKind::kRegular;
                } else if (t.trial == Trial::kRejected) {
                  ++c.rejected;
                } else if (t.trial == Trial::kValid) {
                  ++c.losers;
                }
              }
              counts[b] = c;
            }
          },
          4);
      BlockCount total;
      for (BlockCount& c : counts) {  // counts become each block's offsets
        const BlockCount here = c;
        c = total;
        total.winners += here.winners, total.losers += here.losers, total.rejected += here.rejected;
        total.regular += here.regular;
      }
      const std::size_t winners = total.winners;
      if (winners == 0) break;
      std::vector<std::pair<FaceId, int>>& made = scratch.made;
      std::vector<std::size_t>& winner_of = scratch.winner_of;      // candidate -> winner number
      std::vector<std::size_t>& rejected_at = scratch.rejected_at;  // rejection -> candidate
      std::vector<std::size_t>& wins_before = scratch.wins_before;  // rejection -> winners before it
      made.resize(winners);
      winner_of.resize(count);
      rejected_at.resize(total.rejected);
      wins_before.resize(total.rejected);
      next.resize(total.losers + 4 * winners);
      parallel_chunks(
          blocks, workers,
          [&](std::size_t begin, std::size_t end, unsigned) {
            for (std::size_t b = begin; b < end; ++b) {
              BlockCount at = counts[b];
              for (std::size_t k = b * kNumberingBlock; k < std::min(count, (b + 1) * kNumberingBlock); ++k) {
                const BatchTrial& t = trials[k];
                if (t.winner) {
                  winner_of[k] = at.winners;
                  made[at.winners++] = {candidates[k].edge.face, candidates[k].edge.index};
                } else if (t.trial == Trial::kRejected) {
                  rejected_at[at.rejected] = k;
                  wins_before[at.rejected++] = at.winners;
                } else if (t.trial == Trial::kValid) {
                  next[at.losers++] = candidates[k];
                }
              }
            }
          },
          4);
      t_claim += ms_since(q0);
      q0 = Clock::now();
      const FaceId base = e.mesh_.swap_batch(made, workers);
      t_apply += ms_since(q0);
      q0 = Clock::now();
      budget = budget > winners ? budget - winners : 0;
      // Rejections in order: each doomed vertex and each first rejection of an edge, which is recorded.
      // Records and sequence numbers follow candidate order, winners and recorded rejections interleaved.
      const std::size_t first_record = record.swaps.size();
      const int first_sequence = sequence;
      std::vector<std::size_t>& recorded = scratch.recorded;  // candidates of the recorded rejections
      recorded.clear();
      for (std::size_t r = 0; r < rejected_at.size(); ++r) {
        BatchTrial& t = trials[rejected_at[r]];
        if (!doom_and_mark_rejected(t.swap, t.beneath_inside)) continue;
        const std::size_t slot = wins_before[r] + recorded.size();
        t.swap.kind = t.verdict;
        t.swap.sequence = first_sequence + static_cast<int>(slot);
        if (record.swaps.size() < first_record + slot + 1) record.swaps.resize(first_record + slot + 1);
        record.swaps[first_record + slot] = t.swap;
        ++record.swaps_rejected;
        recorded.push_back(rejected_at[r]);
      }
      record.swaps.resize(first_record + winners + recorded.size());
      sequence = first_sequence + static_cast<int>(winners + recorded.size());
      record.swaps_regular += total.regular;
      record.swaps_complementary += winners - total.regular;
      const std::size_t carried = total.losers, first_entry = entries.size(),
                        first_plane = swap_planes.size();
      entries.resize(first_entry + winners);
      entry_targets.resize(first_entry + winners);
      swap_planes.resize(first_plane + winners);
      if (killed_by_entry.size() < e.mesh_.face_capacity())
        killed_by_entry.resize(e.mesh_.face_capacity(), -1);
      parallel_chunks(
          count, workers,
          [&](std::size_t begin, std::size_t end, unsigned) {
            for (std::size_t k = begin; k < end; ++k) {
              BatchTrial& t = trials[k];
              if (!t.winner) continue;
              const std::size_t w = winner_of[k];
              const FaceId n1 = base + 2 * static_cast<FaceId>(w), n2 = n1 + 1;
              // Its slot: after the winners and the recorded rejections before it.
              const std::size_t slot =
                  w + static_cast<std::size_t>(std::lower_bound(recorded.begin(), recorded.end(), k) -
                                               recorded.begin());
              t.swap.kind = candidates[k].kind;
              t.swap.sequence = first_sequence + static_cast<int>(slot);
              write_swap_entry(static_cast<std::int32_t>(first_entry + w), first_plane + w,
                               candidates[k].edge.face, t.other_face, n1, n2, t.swap);
              record.swaps[first_record + slot] = t.swap;
              Candidate* around = next.data() + carried + 4 * w;
              for (const Edge& edge : edges_around(n1, n2))
                *around++ = {edge, SwapKind::kComplementary};
            }
          },
          4096);
      // touch() on every vertex of every swap, as settle() will dedupe them.
      const std::size_t first_touch = touched.size();
      touched.resize(first_touch + 4 * winners);
      parallel_chunks(
          count, workers,
          [&](std::size_t begin, std::size_t end, unsigned) {
            for (std::size_t k = begin; k < end; ++k) {
              if (!trials[k].winner) continue;
              const std::array<PointIndex, 4> vertices = vertices_of(trials[k].swap);
              std::copy(vertices.begin(), vertices.end(), touched.begin() + first_touch + 4 * winner_of[k]);
            }
          },
          4096);
      touched_unsorted = true;
      candidates.swap(next);
      t_book += ms_since(q0);
    }
    if (phase_times_wanted() && rounds > 0)
      std::fprintf(stderr, "  batched swaps: %d rounds, try %.1f claim %.1f swap %.1f bookkeeping %.1f ms\n",
                   rounds, t_eval, t_claim, t_apply, t_book);
    // What is left goes on as one at a time: regular candidates now, as in the unbatched order.
    for (const Candidate& c : candidates) {
      if (c.kind != SwapKind::kRegular) {
        queue.push_back(c.edge);
      } else if (e.mesh_.alive(c.edge.face)) {
        try_swap(c.edge.face, c.edge.index, SwapKind::kRegular);
      }
    }
  }

  // Fig. 4: a vertex of degree 3 becomes one triangle: when it is concave or flat (not above the plane of
  // its three neighbours), or when it was proven inside the hull (`doomed`).
  bool try_remove(PointIndex v, bool doomed_vertex) {
    if (!e.mesh_.has_vertex(v)) return false;
    e.mesh_.ring(v, ring, ring_faces);
    if (ring.size() != 3) return false;
    const PointIndex a = ring[0], b = ring[1], d = ring[2];
    const int height = orient3d(P(a), P(b), P(d), P(v));
    if (!doomed_vertex && height > 0) return false;  // convex: stays
    // A vertex that came back after a removal sits in a fold, where looking concave proves nothing; removing
    // it again would loop.  The exact finish deals with it if the fold remains.
    if (!doomed_vertex && (e.vertex_flags_.get(v) & kRemovedOnce)) return false;

    RemovalRecord removal;
    removal.vertex = v;
    removal.ring[0] = a, removal.ring[1] = b, removal.ring[2] = d;
    // Valid only if the new triangle covers v seen from c (no foldover), and its outer neighbours are
    // three different faces none of which holds the remaining ring vertex: otherwise the result would
    // hold two congruent triangles back to back.
    // Seen from far below the new triangle (its normal's parallel projection, as for swaps).
    const Vec3d pa = P(a), pb = P(b), pd = P(d);
    const Vec3d centroid{(pa.x + pb.x + pd.x) / 3, (pa.y + pb.y + pd.y) / 3, (pa.z + pb.z + pd.z) / 3};
    const Vec3d view = far_below(centroid, normalized(cross(sub(pb, pa), sub(pd, pa))), extent({pa, pb, pd}));
    // A strictly concave vertex is the apex of a tetrahedron (v, a, b, d) that removal adds whole, so it is
    // valid however folded the three faces look; a flat or doomed one must project inside (a, b, d).
    bool valid = height < 0 || in_cone_from(view, pa, pb, pd, P(v));
    std::array<FaceId, 3> outer{};
    for (int k = 0; k < 3 && valid; ++k) {
      const PointIndex from = ring[k], to = ring[(k + 1) % 3], other = ring[(k + 2) % 3];
      outer[k] = e.mesh_.face(ring_faces[k]).n[e.mesh_.edge_index(ring_faces[k], from, to)];
      const MeshFace& out = e.mesh_.face(outer[k]);
      if (out.v[0] == other || out.v[1] == other || out.v[2] == other) valid = false;
    }
    if (valid && (outer[0] == outer[1] || outer[1] == outer[2] || outer[0] == outer[2])) valid = false;
    if (!valid) {
      removal.rejected = true;
      removal.sequence = sequence++;
      record.removals.push_back(removal);
      ++record.removals_rejected;
      return false;
    }
    const std::vector<FaceId> old_faces = ring_faces;
    const FaceId n = e.mesh_.remove_degree3(v);
    DecisionEntry entry;
    entry.kind = kDecisionRemoval;
    const std::int32_t index = add_entry(entry, n, n);
    for (FaceId f : old_faces)
      note_killed(f, index);
    removal.decision_index = index;
    removal.sequence = sequence++;
    record.removals.push_back(removal);
    ++record.vertices_removed;
    e.vertex_flags_[v] |= kRemovedOnce;
    e.removed_vertices_.push_back(v);
    e.removed_near_.push_back(a);
    for (int k = 0; k < 3; ++k)
      queue.push_back({n, k});
    for (PointIndex p : {a, b, d})
      touch(p);
    return true;
  }

  // Complementary swaps around a doomed vertex until its degree is 3, then its removal (Fig. 4).  Each swap
  // takes one edge of the vertex's star whose quadrilateral is convex seen from c; concave edges first.
  bool take_out(PointIndex w) {
    std::size_t last_degree = SIZE_MAX;
    for (;;) {
      if (!e.mesh_.has_vertex(w)) return true;
      e.mesh_.ring(w, ring, ring_faces);
      if (ring.size() == 3) return try_remove(w, true);
      // Every swap here takes an edge out of w's star, so the degree must fall each round.  On degenerate
      // input (the property test's 1e6-offset cluster) a swap can leave it as it was; stop rather than cycle
      // (the exact finish deals with what remains).
      if (ring.size() >= last_degree || budget == 0) return false;
      last_degree = ring.size();
      --budget;
      // One viewpoint for the whole star: far below w along the mean normal of its faces.
      Vec3d mean{0, 0, 0};
      double size = 0;
      for (std::size_t k = 0; k < ring.size(); ++k) {
        const Vec3d a = P(ring[k]), b = P(ring[(k + 1) % ring.size()]);
        mean = add(mean, normalized(cross(sub(a, P(w)), sub(b, P(w)))));
        size = std::max(size, extent({P(w), a}));
      }
      const Vec3d view = far_below(P(w), normalized(mean), size);
      bool swapped = false;
      for (int pass = 0; pass < 2 && !swapped; ++pass) {
        for (std::size_t k = 0; k < ring.size() && !swapped; ++k) {
          const std::size_t prev = (k + ring.size() - 1) % ring.size(), next = (k + 1) % ring.size();
          // Edge w -> ring[k] lies in face (w, ring[k], ring[k+1]); swapping it gives ring[k+1] - ring[k-1].
          const bool concave = orient3d(P(w), P(ring[k]), P(ring[next]), P(ring[prev])) > 0;
          if (pass == 0 && !concave) continue;
          const FaceId f = ring_faces[k];
          const int i = e.mesh_.edge_index(f, w, ring[k]);
          if (i < 0) continue;  // a ring that does not close cleanly (degenerate input): not this edge
          SwapRecord probe;
          if (swap_validity(w, ring[k], ring[next], ring[prev], probe, &view) != SwapKind::kRegular) continue;
          swapped = try_swap(f, i, SwapKind::kComplementary, &view);
        }
      }
      if (!swapped) return false;
    }
  }

  // Regular swaps are done; now complementary swaps and removals until nothing changes.  Concave swaps add
  // volume and take-outs lower the vertex count, so this terminates in exact arithmetic; the budget guards
  // against cycling on degenerate input (the property test found one: a cluster 1e6 from the origin).
  void reset_budget() { budget = 20 * e.mesh_.face_capacity() + 1000; }

  void settle() {
    reset_budget();
    bool changed = true;
    while (changed && budget > 0) {
      changed = false;
      if (queue.size() >= e.options_.batched_swaps_from) {
        std::vector<Candidate> candidates;
        candidates.reserve(queue.size());
        for (const Edge& edge : queue)
          candidates.push_back({edge, SwapKind::kComplementary});
        queue.clear();
        const std::size_t before = record.swaps_complementary;
        batched_swaps(std::move(candidates), e.options_.batched_swaps_from);
        if (record.swaps_complementary != before) changed = true;
      }
      while (!queue.empty() && budget > 0) {
        const Edge edge = queue.front();
        queue.pop_front();
        if (e.mesh_.alive(edge.face) && try_swap(edge.face, edge.index, SwapKind::kComplementary)) {
          changed = true;
          --budget;
        }
      }
      std::vector<PointIndex> out = std::move(doomed);
      doomed.clear();
      for (PointIndex w : out) {
        if (take_out(w)) changed = true;
        e.vertex_flags_[w] &= static_cast<std::uint8_t>(~kDoomed);
        --doomed_now;
      }
      std::vector<PointIndex> candidates = std::move(touched);
      touched.clear();
      if (touched_unsorted) {
        parallel_sort(candidates);
        candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
        touched_unsorted = false;
      }
      if (candidates.size() >= e.options_.batched_swaps_from) {
        // Many candidates (a batched iteration): find those of degree 3 on all cores first.  One whose
        // degree falls to 3 by an earlier removal here was touched by it, so the next pass sees it.
        std::vector<std::uint8_t> degree3(candidates.size());
        parallel_chunks(
            candidates.size(), hardware_workers(),
            [&](std::size_t begin, std::size_t end, unsigned) {
              for (std::size_t k = begin; k < end; ++k) {
                const PointIndex v = candidates[k];
                if (std::uint8_t* flags = e.vertex_flags_.find(v))
                  *flags &= static_cast<std::uint8_t>(~kTouched);
                degree3[k] = e.mesh_.has_vertex(v) && e.mesh_.degree(v, 4) == 3;
              }
            },
            1024);
        for (std::size_t k = 0; k < candidates.size(); ++k) {
          const PointIndex v = candidates[k];
          if (degree3[k] && e.mesh_.degree(v, 4) == 3 && try_remove(v, false)) changed = true;
        }
      } else {
        for (PointIndex v : candidates)
          e.vertex_flags_[v] &= static_cast<std::uint8_t>(~kTouched);
        for (PointIndex v : candidates) {
          if (e.mesh_.has_vertex(v) && e.mesh_.degree(v, 4) == 3 && try_remove(v, false)) changed = true;
        }
      }
      if (!queue.empty()) changed = true;
      if (budget > 0) --budget;  // an unsigned count: at 0 a plain decrement wrapped round and never ended
    }
  }

  // The separating planes (Fig. 7) of this iteration's refinements and swaps.  Only arithmetic on faces
  // that stay in storage until compact(), so it runs after the edits, on all cores.
  void separating_planes(std::vector<RefinementEntry>& refinement,
                         const std::vector<std::array<FaceId, 3>>& children) {
    parallel_chunks(
        refinement.size(), hardware_workers(),
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t k = begin; k < end; ++k) {
            // Child i is (v[i], v[i+1], apex) of the old face.  plane[i] through the apex and old vertex i
            // separates child i-1 from child i, along the average of their normals; child i is on its
            // positive side.
            const std::array<FaceId, 3>& kids = children[k];
            const Vec3d normal[3] = {unit_normal(kids[0]), unit_normal(kids[1]), unit_normal(kids[2])};
            const Vec3d apex = P(refinement[k].apex);
            for (int i = 0; i < 3; ++i) {
              const Vec3d along = add(normal[i], normal[(i + 2) % 3]);
              const Vec3d inside = P(e.mesh_.face(kids[(i + 1) % 3]).v[0]);
              refinement[k].plane[i] = plane_through_edge(apex, P(e.mesh_.face(kids[i]).v[0]), along, inside);
            }
          }
        },
        512);
    parallel_chunks(
        swap_planes.size(), hardware_workers(),
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t k = begin; k < end; ++k) {
            const PendingPlane& p = swap_planes[k];
            const MeshFace& n1 = e.mesh_.face(p.n1);  // (x, u, y)
            const Vec3d along = add(unit_normal(p.n1), unit_normal(p.n2));
            entries[p.entry].plane = plane_through_edge(P(n1.v[0]), P(n1.v[2]), along, P(p.u));
          }
        },
        512);
    swap_planes.clear();
  }

  std::int32_t route_code(FaceId work, const std::vector<FaceId>& remap) const {
    if (remap[work] != kNoFace) return static_cast<std::int32_t>(remap[work]);
    return -(killed_by_entry.at(work) + 1);
  }
};

Engine::Engine(std::vector<Point3> points, std::unique_ptr<Backend> backend, EngineOptions options)
    : points_(std::move(points)), backend_(std::move(backend)), options_(options) {
  if (!backend_) throw std::invalid_argument("Engine needs a backend");
  if (const char* from = std::getenv("CUDAHULL_BATCHED_SWAPS_FROM"))
    options_.batched_swaps_from = std::strtoull(from, nullptr, 10);
  if (points_.size() >= 0xffffffffu) throw std::invalid_argument("too many points (at most 2^32 - 2)");
}

Engine::~Engine() = default;

IterationRecord Engine::step() {
  if (done_) throw std::logic_error("Engine::step() after done()");
  if (!started_) {
    started_ = true;
    last_record_ = initialize();
  } else {
    last_record_ = iterate();
  }
  return last_record_;
}

void Engine::run(const std::function<void(const IterationRecord&)>& on_step) {
  while (!done_) {
    IterationRecord r = step();
    if (on_step) on_step(r);
  }
}

bool Engine::write_point_states_on_device(std::int32_t* device_out, std::size_t count,
                                          const std::vector<PointIndex>& vertices) {
  if (!started_ || dimension_ != 3 || count != points_.size()) return false;
  return backend_->write_point_states_on_device(device_out, count, vertices);
}

std::vector<std::string> Engine::explain_route(PointIndex point, std::int32_t old_face) const {
  std::vector<std::string> lines;
  const IterationTables& t = tables_;
  if (!started_ || dimension_ != 3 || point >= points_.size()) return {"no 3-d step to explain"};
  const Point3& x = points_[point];
  auto route = [](std::int32_t code) {
    return code == kRouteInternal ? std::string("internal")
           : code < 0             ? "decision[" + std::to_string(-code - 1) + "]"
                                  : "face " + std::to_string(code);
  };
  auto sign = [&](const SeparatingPlane& p) { return plane_value(p, x) >= 0 ? '+' : '-'; };
  if (std::find(t.retired.begin(), t.retired.end(), point) != t.retired.end()) {
    return {"point " + std::to_string(point) + " was the apex of a refined face: it became a vertex",
            "vertex"};
  }
  std::int32_t code;
  if (!t.initial_cells.empty()) {
    code = 0;
    for (std::int32_t f = 0; f < 4; ++f) {
      const SeparatingPlane* cell = t.initial_cells.data() + 3 * f;
      if (sign(cell[0]) == '+' && sign(cell[1]) == '+' && sign(cell[2]) == '+') {
        code = f;
        break;
      }
    }
    lines.push_back("first distribution (section 3.1): in the cell of tetrahedron face " +
                    std::to_string(code));
  } else {
    if (old_face < 0 || static_cast<std::size_t>(old_face) >= t.old_face_split.size())
      return {"point " + std::to_string(point) +
              " had no face before this step (it was internal or a vertex)"};
    const std::int32_t split = t.old_face_split[old_face];
    if (split < 0) {
      code = t.old_face_route[old_face];
      lines.push_back("old face " + std::to_string(old_face) + " was not refined; its points go to " +
                      route(code));
    } else {
      const RefinementEntry& r = t.refinement[split];
      const char s0 = sign(r.plane[0]), s1 = sign(r.plane[1]), s2 = sign(r.plane[2]);
      const int child = (s0 == '+' && s1 == '-')   ? 0
                        : (s1 == '+' && s2 == '-') ? 1
                        : (s2 == '+' && s0 == '-') ? 2
                                                   : 0;
      code = r.child[child];
      lines.push_back("old face " + std::to_string(old_face) + " was refined at apex " +
                      std::to_string(r.apex) + " (refinement[" + std::to_string(split) + "]): planes " + s0 +
                      s1 + s2 + " -> child " + std::to_string(child) + " -> " + route(code));
    }
    while (code < 0 && code != kRouteInternal) {
      const std::int32_t k = -code - 1;
      const DecisionEntry& e = t.decision[k];
      if (e.kind == kDecisionRemoval) {
        code = e.above;
        lines.push_back("decision[" + std::to_string(k) + "]: a vertex removal -> " + route(code));
      } else {
        const bool above = plane_value(e.plane, x) >= 0;
        code = above ? e.above : e.below;
        lines.push_back("decision[" + std::to_string(k) + "]: " + (above ? "above" : "below") +
                        " the swap's separating plane -> " + route(code));
      }
    }
  }
  if (code == kRouteInternal) {
    lines.push_back("internal");
    return lines;
  }
  // The exact verdict (routing.hpp): strictly above the face, inside the tetrahedron (c, face), or a stray
  // that walks on to a neighbour.
  std::int32_t g = code;
  for (int step = 0; step < kMaxStrayWalk; ++step) {
    int exit_edge = -1;
    const PointVerdict verdict = face_verdict(geometry_[g], interior_, x, &exit_edge);
    if (verdict == kVerdictExternal) {
      lines.push_back("exact: strictly above face " + std::to_string(g) + ": external");
      lines.push_back("face " + std::to_string(g));
      return lines;
    }
    if (verdict == kVerdictInternal) {
      lines.push_back("exact: inside the tetrahedron of face " + std::to_string(g) +
                      " and the interior point: proven inside the hull");
      lines.push_back("internal");
      return lines;
    }
    if (exit_edge < 0) break;
    g = geometry_[g].neighbor[exit_edge];
    lines.push_back("exact: below that face but beyond its radial plane " + std::to_string(exit_edge) +
                    ": walks to face " + std::to_string(g));
  }
  const std::int32_t found =
      locate_point(x, g, geometry_.data(), static_cast<std::int32_t>(geometry_.size()), interior_, 0);
  lines.push_back("exact: exhaustive search over all faces -> " + route(found));
  lines.push_back(found == kRouteInternal ? "internal" : "face " + std::to_string(found));
  return lines;
}

std::vector<std::int32_t> Engine::point_faces() const {
  std::vector<std::int32_t> out;
  if (started_ && dimension_ == 3) backend_->point_faces(out);
  for (auto& f : out) {
    if (f < 0) f = -1;
  }
  return out;
}

void Engine::face_geometry(FaceGeometryArray& faces, const std::vector<FaceId>* remap) const {
  const std::size_t count = mesh_.live_faces();
  // Reuses the spare buffer: a fresh 100 MB array costs page faults every iteration.  When it must grow, a
  // new one with room to spare, its old contents not copied (every face is written below), and its pages
  // first touched by the parallel passes below rather than by one core (on a 1M-point sphere, growing
  // these arrays cost ~600 ms on 2 cores, more than a third of the host time).  The spare room is only
  // address space until written, so it is generous.
  if (count > faces.capacity()) {
    FaceGeometryArray grown;
    grown.reserve(2 * count);
    faces.swap(grown);
  }
  faces.resize(count);
  // Faces that survived the iteration keep their corners and tetrahedron signs (4 exact orient3d each);
  // compaction keeps the order, so this is one forward pass.  Only new faces are computed.
  std::vector<std::uint8_t> known(count, 0);
  if (remap != nullptr) {
    const std::size_t old_count = std::min(geometry_.size(), remap->size());
    parallel_chunks(
        old_count, hardware_workers(),
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t o = begin; o < end; ++o) {
            const FaceId f = (*remap)[o];
            if (f == kNoFace) continue;
            faces[f] = geometry_[o];
            known[f] = 1;
          }
        },
        16384);
  }
  parallel_chunks(
      count, hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t f = begin; f < end; ++f) {
          const MeshFace& face = mesh_.face(static_cast<FaceId>(f));
          for (int k = 0; k < 3; ++k)
            faces[f].neighbor[k] = static_cast<std::int32_t>(face.n[k]);
        }
      },
      16384);
  // The new faces sit together at the end (compaction keeps the id order), so they are listed first and
  // shared out evenly: split by position, one core would get them all.
  std::vector<FaceId> fresh;
  for (std::size_t f = 0; f < count; ++f) {
    if (!known[f]) fresh.push_back(static_cast<FaceId>(f));
  }
  parallel_chunks(
      fresh.size(), hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < end; ++k) {
          const MeshFace& face = mesh_.face(fresh[k]);
          FaceGeometry& g = faces[fresh[k]];
          for (int i = 0; i < 3; ++i)
            g.v[i] = points_[face.v[i]];
          face_tetrahedron_signs(interior_, g.v, g.tet);
        }
      },
      2048);
}

FaceCell Engine::face_cell(FaceId f) const {
  auto P = [&](PointIndex i) { return to_vec3d(points_[i]); };
  auto unit_normal = [&](FaceId g) {
    const MeshFace& face = mesh_.face(g);
    return normalized(cross(sub(P(face.v[1]), P(face.v[0])), sub(P(face.v[2]), P(face.v[0]))));
  };
  const MeshFace& face = mesh_.face(f);
  FaceCell cell;
  const Vec3d n = unit_normal(f);
  cell.face_plane = {n.x, n.y, n.z, -dot(n, P(face.v[0]))};
  for (int i = 0; i < 3; ++i) {
    const Vec3d along = add(n, unit_normal(face.n[i]));
    cell.edge_plane[i] =
        plane_through_edge(P(face.v[i]), P(face.v[(i + 1) % 3]), along, P(face.v[(i + 2) % 3]));
  }
  return cell;
}

IterationRecord Engine::initialize() {
  const auto t0 = Clock::now();
  IterationRecord record;
  record.iteration = iteration_++;
  const std::size_t n = points_.size();
  auto finish_lower = [&](int dim, const std::string& why) {
    dimension_ = dim;
    result_ = exact_hull(points_);
    record.note = why;
    record.host_ms = ms_since(t0);
    done_ = true;
    return record;
  };
  if (n == 0) return finish_lower(-1, "no points");
  record.external_before = n;

  const auto tb = Clock::now();
  backend_->upload_points(points_);
  record.upload_ms = ms_since(tb);
  auto [p0, p1] = backend_->extremes_x();
  double backend_ms = ms_since(tb);
  auto P = [&](PointIndex i) { return to_vec3d(points_[i]); };

  // Section 3.1, with each choice confirmed exactly: the ranking is in floating point, so a "furthest"
  // point can still be exactly collinear or coplanar; then any exact witness will do, and none at all means
  // the input is lower-dimensional.
  if (points_[p0].x == points_[p1].x) {
    // Every x is equal: the points lie in a plane, on a line, or are one point; exact_hull finds the answer.
    const int dimension = affine_dimension(points_);
    return finish_lower(
        dimension, "degenerate input: all points share one x (dimension " + std::to_string(dimension) + ")");
  }
  auto tb2 = Clock::now();
  PointIndex p2 = backend_->furthest_from_line(p0, p1);
  if (collinear3d(P(p0), P(p1), P(p2))) {
    p2 = kNoPoint;
    for (PointIndex i = 0; i < n && p2 == kNoPoint; ++i) {
      if (!collinear3d(P(p0), P(p1), P(i))) p2 = i;
    }
    if (p2 == kNoPoint) return finish_lower(1, "degenerate input: all points are collinear (dimension 1)");
  }
  PointIndex p3 = backend_->furthest_from_plane(p0, p1, p2);
  backend_ms += ms_since(tb2);
  if (orient3d(P(p0), P(p1), P(p2), P(p3)) == 0) {
    p3 = kNoPoint;
    for (PointIndex i = 0; i < n && p3 == kNoPoint; ++i) {
      if (orient3d(P(p0), P(p1), P(p2), P(i)) != 0) p3 = i;
    }
    if (p3 == kNoPoint) return finish_lower(2, "degenerate input: all points are coplanar (dimension 2)");
  }
  dimension_ = 3;
  if (orient3d(P(p0), P(p1), P(p2), P(p3)) > 0) std::swap(p1, p2);  // p3 must lie below (p0, p1, p2)
  mesh_.make_tetrahedron(p0, p1, p2, p3);
  vertex_flags_.clear();
  used_vertices_ = {p0, p1, p2, p3};

  // The interior reference point c: the tetrahedron's centroid, confirmed strictly inside exactly.  It
  // anchors every discard (a point is dropped only inside a tetrahedron of c and a face).
  interior_ = {(P(p0).x + P(p1).x + P(p2).x + P(p3).x) / 4, (P(p0).y + P(p1).y + P(p2).y + P(p3).y) / 4,
               (P(p0).z + P(p1).z + P(p2).z + P(p3).z) / 4};
  for (FaceId f = 0; f < 4; ++f) {
    const MeshFace& face = mesh_.face(f);
    if (orient3d(P(face.v[0]), P(face.v[1]), P(face.v[2]), interior_) >= 0) {
      // A tetrahedron so flat that its rounded centroid is not inside: finish exactly on all points.
      record.repairs = 1;
      return finish_lower(3, "tetrahedron too flat for an interior point: exact hull of all points");
    }
  }

  IterationTables& tables = tables_;
  tables.clear();
  tables.interior = interior_;
  for (FaceId f = 0; f < 4; ++f) {
    const FaceCell cell = face_cell(f);
    for (int i = 0; i < 3; ++i)
      tables.initial_cells.push_back(cell.edge_plane[i]);
  }
  face_geometry(tables.faces);
  tables.old_face_split.assign(1, -1);  // unused: the first distribution goes by the initial cells
  tables.old_face_route.assign(1, 0);
  record.host_ms = ms_since(t0) - backend_ms;
  const auto tb3 = Clock::now();
  backend_->distribute_points(tables);
  external_ = backend_->compact_index_array();
  backend_->get_extreme_points(extremes_);
  record.backend_ms = backend_ms + ms_since(tb3);
  geometry_.swap(tables.faces);  // the old geometry stays as the next iteration's buffer
  record.faces_after = 4;
  record.external_after = external_;
  record.bytes_to_backend = backend_->bytes_to_backend();
  record.bytes_from_backend = backend_->bytes_from_backend();
  record.refined_apexes = {p0, p1, p2, p3};
  if (external_ == 0) finish(record);
  return record;
}

IterationRecord Engine::iterate() {
  const auto t0 = Clock::now();
  const std::uint64_t to_before = backend_->bytes_to_backend(), from_before = backend_->bytes_from_backend();
  IterationRecord record;
  record.iteration = iteration_++;
  record.faces_before = mesh_.live_faces();
  record.external_before = external_;
  Impl impl(*this, record);

  // Refinement (Fig. 3a): every face with external points splits at its furthest point.
  const FaceId old_faces = static_cast<FaceId>(mesh_.face_capacity());
  std::vector<RefinementEntry> refinement;      // one per refined face (Fig. 7's refinement[])
  std::vector<std::array<FaceId, 3>> children;  // work ids, one triple per refinement entry
  std::vector<Edge> regular_candidates;
  std::vector<FaceId> refined;
  for (FaceId f = 0; f < old_faces; ++f) {
    if (extremes_[f].count != 0) refined.push_back(f);
  }
  const std::size_t refined_count = refined.size();
  // Room for every vertex the edits may flag (every point that was ever a vertex, the apexes included), so
  // touch() never rehashes.  (Not vertices + old faces: on a 1M-point sphere that bound grew the table
  // to 8M slots in one iteration, a ~100 ms rehash.)
  vertex_flags_.reserve(used_vertices_.size() + refined_count);
  refinement.resize(refined_count);
  record.refined_apexes.resize(refined_count);
  record.refined_faces.resize(refined_count);
  const std::size_t first_used = used_vertices_.size();
  used_vertices_.resize(first_used + refined_count);
  const bool batched = refined_count >= options_.batched_swaps_from;
  if (batched) impl.touched.resize(3 * refined_count);
  parallel_chunks(
      refined_count, hardware_workers(),
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < end; ++k) {
          const FaceId f = refined[k];
          RefinementEntry& entry = refinement[k];
          entry.face = f;
          entry.apex = extremes_[f].furthest;
          record.refined_apexes[k] = entry.apex;
          record.refined_faces[k] = mesh_.face(f).v;
          used_vertices_[first_used + k] = entry.apex;
          if (batched) std::copy_n(mesh_.face(f).v.begin(), 3, impl.touched.begin() + 3 * k);
        }
      },
      16384);
  if (batched) {
    impl.touched_unsorted = true;  // settle() sorts and dedupes them
  } else {
    for (FaceId f : refined) {
      for (PointIndex v : mesh_.face(f).v)
        impl.touch(v);
    }
  }
  const double tp0 = ms_since(t0);
  const FaceId first_child = mesh_.split_batch(refined, record.refined_apexes, hardware_workers());
  const double tp1 = ms_since(t0);
  children.resize(refined.size());
  regular_candidates.reserve(3 * refined.size());
  for (std::size_t k = 0; k < refined.size(); ++k) {
    for (FaceId i = 0; i < 3; ++i) {
      children[k][i] = first_child + 3 * static_cast<FaceId>(k) + i;
      regular_candidates.push_back({children[k][i], 0});
    }
  }
  record.faces_refined = record.refined_apexes.size();

  // Regular swaps of the refined faces' old edges, then complementary swaps and removals (Figs. 3b, 4).
  // (Fewer than batched_swaps_from candidates go one at a time, in order, inside batched_swaps().)
  std::vector<Impl::Candidate> candidates;
  candidates.reserve(regular_candidates.size());
  for (const Edge& edge : regular_candidates)
    candidates.push_back({edge, SwapKind::kRegular});
  impl.reset_budget();
  impl.batched_swaps(std::move(candidates), options_.batched_swaps_from);
  const double tp2 = ms_since(t0);
  impl.settle();
  const double tp3 = ms_since(t0);
  impl.separating_planes(refinement, children);
  const double tp4 = ms_since(t0);

  // Renumber the faces and turn work ids into route codes (Fig. 7).
  const std::vector<FaceId>& remap = mesh_.compact();
  IterationTables& tables = tables_;
  tables.clear();
  tables.interior = interior_;
  tables.refinement = std::move(refinement);
  tables.old_face_split.assign(old_faces, -1);
  tables.old_face_route.resize(old_faces);
  const unsigned workers = hardware_workers();
  parallel_chunks(
      tables.refinement.size(), workers,
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < end; ++k) {
          RefinementEntry& r = tables.refinement[k];
          tables.old_face_split[r.face] = static_cast<std::int32_t>(k);
          for (int i = 0; i < 3; ++i)
            r.child[i] = impl.route_code(children[k][i], remap);
        }
      },
      16384);
  parallel_chunks(
      old_faces, workers,
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t f = begin; f < end; ++f)
          tables.old_face_route[f] =
              tables.old_face_split[f] < 0 ? impl.route_code(static_cast<FaceId>(f), remap) : 0;
      },
      16384);
  tables.retired = record.refined_apexes;
  tables.decision = impl.entries;
  parallel_chunks(
      tables.decision.size(), workers,
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < end; ++k) {
          tables.decision[k].above = impl.route_code(impl.entry_targets[k][0], remap);
          tables.decision[k].below = impl.route_code(impl.entry_targets[k][1], remap);
        }
      },
      16384);
  const double tp5 = ms_since(t0);
  face_geometry(tables.faces, &remap);
  record.decision_entries = tables.decision.size();
  record.host_ms = ms_since(t0);
  if (phase_times_wanted())
    std::fprintf(stderr,
                 "iteration %d host ms: collect %.2f split %.2f regular+batched %.2f settle %.2f planes %.2f "
                 "tables %.2f geometry %.2f\n",
                 record.iteration, tp0, tp1 - tp0, tp2 - tp1, tp3 - tp2, tp4 - tp3, tp5 - tp4,
                 record.host_ms - tp5);

  // Algorithm 2 on the backend: distribute, compact, extremes.
  const auto tb = Clock::now();
  backend_->distribute_points(tables);
  external_ = backend_->compact_index_array();
  backend_->get_extreme_points(extremes_);
  record.backend_ms = ms_since(tb);
  geometry_.swap(tables.faces);  // the old geometry stays as the next iteration's buffer

  record.faces_after = mesh_.live_faces();
  record.external_after = external_;
  record.bytes_to_backend = backend_->bytes_to_backend() - to_before;
  record.bytes_from_backend = backend_->bytes_from_backend() - from_before;
  if (options_.keep_decisions) record.decisions = tables.decision;
  stalled_ = external_ < record.external_before ? 0 : stalled_ + 1;
  if (external_ == 0 || stalled_ >= kStallLimit) finish(record);
  return record;
}

void Engine::finish(IterationRecord& record) {
  const auto t0 = Clock::now();
  auto P = [&](PointIndex i) { return to_vec3d(points_[i]); };
  // The mesh is the exact hull when every edge is strictly convex (so every vertex is strictly extreme), c
  // is inside, and every vertex it ever dropped lies inside it.  Everything else was discarded inside a
  // tetrahedron of c and input points, so nothing outside is left.
  // The edges that are not strictly convex, each once (from its lower face id), in id order.  Parallel:
  // on a sphere of 1M points this scan covers 3M edges.
  // With `from_geometry` (geometry_ matches the mesh) corners are read from geometry_, where they lie next
  // to each other, instead of from the input points: fewer cache misses on a 2M-face mesh.
  auto faulty_edges = [&](bool from_geometry) {
    const FaceId capacity = static_cast<FaceId>(mesh_.face_capacity());
    const unsigned workers = hardware_workers();
    std::vector<std::vector<Edge>> found(workers);
    parallel_chunks(
        capacity, workers,
        [&](std::size_t begin, std::size_t end, unsigned w) {
          for (FaceId f = static_cast<FaceId>(begin); f < end; ++f) {
            if (!mesh_.alive(f)) continue;
            const MeshFace& face = mesh_.face(f);
            Vec3d corner[3];
            for (int k = 0; k < 3; ++k)
              corner[k] = from_geometry ? to_vec3d(geometry_[f].v[k]) : P(face.v[k]);
            for (int i = 0; i < 3; ++i) {
              const FaceId g = face.n[i];
              if (g < f) continue;
              const int j = mesh_.edge_index(g, face.v[(i + 1) % 3], face.v[i]);
              const Vec3d y =
                  from_geometry ? to_vec3d(geometry_[g].v[(j + 2) % 3]) : P(mesh_.face(g).v[(j + 2) % 3]);
              if (orient3d(corner[0], corner[1], corner[2], y) >= 0) found[w].push_back({f, i});
            }
          }
        },
        16384);
    std::vector<Edge> all;
    for (const auto& part : found)
      all.insert(all.end(), part.begin(), part.end());
    return all;
  };
  // Faults: faulty edges plus faces that c is not strictly below (geometry_ matches the compacted mesh).
  auto count_faults = [&] {
    std::size_t count = faulty_edges(true).size();
    for (const FaceGeometry& g : geometry_)
      count += g.tet[3] >= 0 ? 1 : 0;
    return count;
  };
  std::size_t faults = count_faults();
  const double tf_check = ms_since(t0);
  if (faults > 0) {
    // No point is outside any more, but rejected swaps have left concave edges: apply the paper's local
    // steps (swaps, complementary swaps, removals) from each faulty edge until nothing changes; settle()
    // follows the changes to the neighbouring edges and vertices.
    Impl impl(*this, record);
    // The repairs go on the step's record after its own edits: their sequence numbers continue.
    impl.sequence = static_cast<int>(record.swaps.size() + record.removals.size());
    for (int round = 0; round < 8; ++round) {
      const std::vector<Edge> faulty = faulty_edges(false);
      if (faulty.empty()) break;
      for (const Edge& edge : faulty) {
        impl.queue.push_back(edge);
        for (PointIndex v : mesh_.face(edge.face).v)
          impl.touch(v);
      }
      const std::size_t before = record.swaps.size() + record.removals.size();
      impl.rejected_edges.clear();
      impl.settle();
      // settle() stops with edges still queued when its guard budget runs out; compaction renumbers the
      // faces, so those edges would name other faces, or none (the next round starts from the faulty edges).
      impl.queue.clear();
      mesh_.compact();
      if (record.swaps.size() + record.removals.size() == before) break;
    }
    face_geometry(geometry_);
    faults = count_faults();
  }
  const FaceId faces = static_cast<FaceId>(mesh_.face_capacity());
  if (faults == 0) {
    // The mesh is convex with c inside: locate each dropped vertex (a point leaves the mesh only by a
    // removal, Fig. 4) by a walk through the radial cones.
    // The walk starts at a face of a vertex of the dropped vertex's ring, when that is still a vertex: a few
    // steps away instead of a walk across the mesh from face 0 (on a 10M-point ball ~1,200 walks of up to
    // ~700 faces).
    std::vector<std::pair<PointIndex, PointIndex>> dropped(removed_vertices_.size());
    for (std::size_t k = 0; k < dropped.size(); ++k)
      dropped[k] = {removed_vertices_[k], removed_near_[k]};
    std::sort(dropped.begin(), dropped.end());
    dropped.erase(std::unique(dropped.begin(), dropped.end(),
                              [](const auto& a, const auto& b) { return a.first == b.first; }),
                  dropped.end());
    const FaceGeometryArray& geometry = geometry_;
    const int walk = 64 + 4 * static_cast<int>(std::sqrt(static_cast<double>(geometry.size())));
    std::atomic<std::size_t> outside{0};
    parallel_chunks(
        dropped.size(), hardware_workers(),
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t k = begin; k < end; ++k) {
            const auto [r, near] = dropped[k];
            if (mesh_.has_vertex(r)) continue;
            const FaceId near_face = mesh_.face_of_vertex(near);
            const auto start = near_face < geometry.size() ? static_cast<std::int32_t>(near_face) : 0;
            const std::int32_t found =
                locate_point(points_[r], start, geometry.data(), static_cast<std::int32_t>(geometry.size()),
                             interior_, walk);
            if (found != kRouteInternal) outside.fetch_add(1, std::memory_order_relaxed);
          }
        },
        64);
    faults += outside.load();
  }
  faults += external_;  // after a stall: points still outside the mesh
  const double tf_dropped = ms_since(t0);
  if (faults == 0) {
    result_ = HullMesh{};
    result_.dimension = 3;
    result_.vertex_ids = mesh_.vertices();
    const std::vector<PointIndex>& ids = result_.vertex_ids;
    result_.vertices.resize(ids.size());
    result_.triangles.resize(faces);
    // Corners renumbered on all cores: through a per-point table when most points are vertices (a
    // sphere), else through a hash map of the vertices (a binary search in the sorted ids cost 6-12 ms for
    // the 28K faces of a 10M-point ball: 84K searches, each ~14 mispredicted branches).
    std::vector<std::uint32_t> dense;
    PointMap<std::uint32_t> sparse;
    if (8 * ids.size() >= points_.size()) {
      dense.resize(points_.size());
      parallel_chunks(ids.size(), hardware_workers(), [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < end; ++k)
          dense[ids[k]] = static_cast<std::uint32_t>(k);
      });
    } else {
      sparse.reserve(ids.size());
      for (std::size_t k = 0; k < ids.size(); ++k)
        sparse[ids[k]] = static_cast<std::uint32_t>(k);
    }
    auto local = [&](PointIndex v) { return dense.empty() ? sparse.get(v) : dense[v]; };
    parallel_chunks(
        std::max<std::size_t>(faces, ids.size()), hardware_workers(),
        [&](std::size_t begin, std::size_t end, unsigned) {
          for (std::size_t k = begin; k < std::min<std::size_t>(end, ids.size()); ++k)
            result_.vertices[k] = points_[ids[k]];
          for (std::size_t f = begin; f < std::min<std::size_t>(end, faces); ++f) {
            const MeshFace& face = mesh_.face(static_cast<FaceId>(f));
            result_.triangles[f] = {local(face.v[0]), local(face.v[1]), local(face.v[2])};
          }
        },
        65536);
  } else {
    // The paper's local procedure stopped short (coplanar or cospherical input): finish exactly from the
    // candidates, which contain every extreme point.
    // Points still external (only after a stall) are candidates too.
    std::sort(used_vertices_.begin(), used_vertices_.end());
    used_vertices_.erase(std::unique(used_vertices_.begin(), used_vertices_.end()), used_vertices_.end());
    std::vector<PointIndex> candidates = used_vertices_;
    if (external_ > 0) {
      const std::vector<std::int32_t> faces_of_points = point_faces();
      for (PointIndex i = 0; i < faces_of_points.size(); ++i) {
        if (faces_of_points[i] >= 0) candidates.push_back(i);
      }
      std::sort(candidates.begin(), candidates.end());
      candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    }
    result_ = exact_hull(points_, candidates);
    record.repairs += faults;
    record.note = "finished by an exact hull of " + std::to_string(candidates.size()) +
                  " candidate vertices (" + std::to_string(faults) + " non-convex edges or outside vertices)";
  }
  record.host_ms += ms_since(t0);
  if (phase_times_wanted())
    std::fprintf(stderr, "finish host ms %.2f: check %.2f dropped %.2f result %.2f\n", ms_since(t0), tf_check,
                 tf_dropped - tf_check, ms_since(t0) - tf_dropped);
  done_ = true;
}

}  // namespace cudahull
