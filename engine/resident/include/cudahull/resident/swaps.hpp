// The swaps and removals of the resident engine (Figs. 3b, 4, 5), in conflict-free rounds, and the state
// of a run of rounds on an executor that loops them itself.
//
// design:
//   work     the faces a round looks at: those the last round made, and those stamped for it (next to
//            its edits, or whose candidate lost a claim)
//   find     per work face, its first candidate: a concave edge it owns whose swap keeps both new faces'
//            cones proper (the foldover test of Fig. 5, seen from c), else a vertex of degree 3 it owns
//            that is concave or flat and whose removal keeps the new face's cone proper (Fig. 4)
//   claim    each candidate claims the faces it kills with a 64-bit atomicMax of (round, ~candidate id)
//   judge    the holders of all their claims win; numbered in face order by a prefix sum
//   apply    each winner writes its new faces and one decision entry (Fig. 7), kills its faces and stamps
//            the faces around for the next round; the next round's FixLinks points their links at the
//            new faces
//   stop     when a round has no candidate; the rounds never depend on the thread count or executor
#pragma once

#include <cstddef>

#include "cudahull/resident/star_mesh.hpp"

namespace cudahull::resident {

// A candidate edit: the faces it kills (claimed) and the faces around them (stamped for the next round).
struct Candidate {
  u32 kind = kNone;    // kSwap or kRemoval, or kNone
  u32 id = 0;          // 6 f + slot: what it claims with
  u32 faces[6] = {};   // swap: f, g, A (across x->u), B (u->y), C (y->v), D (v->x); removal: f, h,
                       // t, the outer faces across a->b, b->d, d->a
  u32 vertex[4] = {};  // swap: u, v, x, y; removal: v, a, b, d
};

// faces[0 .. claimed_faces(c)): the faces a candidate kills, which it claims (the rest are the faces around).
CUDAHULL_HD inline u32 claimed_faces(const Candidate& c) {
  return c.kind == kSwap ? 2u : c.kind == kRemoval ? 3u : 0u;
}

// What a candidate's id claims with in round `round`: later rounds win over stale claims, and within a
// round the lowest id.
CUDAHULL_HD inline u64 claim_key(u32 round, u32 candidate) {
  return (static_cast<u64>(round) << 32) | static_cast<u64>(~candidate);
}

// Face f and its three neighbours, read in three waves (f's corners and links, the neighbours' corners
// and links, the six points) so that a thread waits for three loads in a row rather than one per test.
template <class Point>
struct Around {
  u32 f;
  u32 v[3], n[3];          // f
  u32 gv[3][3], gn[3][3];  // neighbour i = n[i]: corners and links
  int j[3];                // the slot of edge v[i+1] -> v[i] in neighbour i, or -1
  Vec3d p[3], y[3];        // f's corners; neighbour i's corner opposite the shared edge (when j[i] >= 0)

  CUDAHULL_HD void gather(const MeshView<Point>& m, u32 face) {
    f = face;
    for (int k = 0; k < 3; ++k) {
      v[k] = m.fv[3 * f + k];
      n[k] = m.fn[3 * f + k];
    }
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) {
        gv[i][k] = m.fv[3 * n[i] + k];
        gn[i][k] = m.fn[3 * n[i] + k];
      }
    }
    for (int i = 0; i < 3; ++i) {
      j[i] = -1;
      for (int s = 0; s < 3; ++s) {
        if (gv[i][s] == v[(i + 1) % 3] && gv[i][(s + 1) % 3] == v[i]) j[i] = s;
      }
    }
    for (int k = 0; k < 3; ++k)
      p[k] = m.P(v[k]);
    for (int i = 0; i < 3; ++i) {
      if (j[i] >= 0) y[i] = m.P(gv[i][(j[i] + 2) % 3]);
    }
  }
  CUDAHULL_HD u32 apex(int i) const { return gv[i][(j[i] + 2) % 3]; }
};

// Records (the viewer, --trace): the candidates a round turned down, as FindCandidate meets them.  Only
// the recording driver's rounds log them (FindCandidate<Point, RejectionLog>); the fast paths' NoLog
// compiles the logging away.
enum RejectionKind : u32 {
  kRejectFoldover = 0,     // a swap whose new faces would not keep c strictly below (Fig. 5, seen from c)
  kRejectNotManifold = 1,  // a swap whose new edge is already an edge of the mesh
  kRejectRemoval = 2,      // a degree-3 concave vertex whose removal would fold over or not be a 2-manifold
};
struct Rejection {
  u32 kind, round, id;  // id: 6 f + slot, as Candidate::id
  u32 vertex[4];        // swap: u, v, x, y; removal: v, a, b, d
};
struct NoLog {
  CUDAHULL_HD void add(u32, u32, u32, u32, u32, u32) const {}
};
struct RejectionLog {
  Rejection* at = nullptr;
  u32* count = nullptr;
  u32 capacity = 0, round = 0;
  // Each round's first decision entry, from round first_round on (the records' round boundaries).
  u32* round_first_entry = nullptr;
  u32 first_round = 0, round_capacity = 0;
  CUDAHULL_HD void add(u32 kind, u32 id, u32 a, u32 b, u32 c, u32 d) const {
    if (!at) return;
    const u32 k = atomic_add_u32(count, 1);
    if (k < capacity) at[k] = Rejection{kind, round, id, {a, b, c, d}};
  }
};

template <class Point, class Log = NoLog>
struct FindCandidate {
  MeshView<Point> m;
  Log log;

  // Edge i of f, owned by f when f is the lower of its two faces: a concave edge whose swap keeps both new
  // faces' cones proper.
  CUDAHULL_HD bool swap(const Around<Point>& a, int i, Candidate& out) const {
    const u32 f = a.f, g = a.n[i];
    const int j = a.j[i];
    if (g < f || j < 0) return false;
    const int iv = (i + 1) % 3, ix = (i + 2) % 3;
    const Vec3d &pu = a.p[i], &pv = a.p[iv], &px = a.p[ix], &py = a.y[i];
    if (orient3d(pu, pv, px, py) <= 0) return false;  // convex or flat
    if (orient3d(m.c, px, pu, py) <= 0 || orient3d(m.c, py, pv, px) <= 0) {
      log.add(kRejectFoldover, 6 * f + static_cast<u32>(i), a.v[i], a.v[iv], a.v[ix], a.apex(i));
      return false;
    }
    const u32 A = a.n[ix], D = a.n[iv], B = a.gn[i][(j + 1) % 3], C = a.gn[i][(j + 2) % 3];
    if (A == B || C == D || A == g || B == f || C == f || D == g) {  // not a 2-manifold
      log.add(kRejectNotManifold, 6 * f + static_cast<u32>(i), a.v[i], a.v[iv], a.v[ix], a.apex(i));
      return false;
    }
    out = Candidate{kSwap, 0, {f, g, A, B, C, D}, {a.v[i], a.v[iv], a.v[ix], a.apex(i)}};
    return true;
  }

  // Corner k of f: a vertex v of degree 3 (faces f = (v, a, b), h = (v, d, a), t = (v, b, d)), owned by
  // the lowest of its faces, concave or flat, whose removal keeps the new face's cone proper.  h is
  // neighbour k and t neighbour k + 2; d is h's apex over the edge a -> v.
  CUDAHULL_HD bool removal(const Around<Point>& r, int k, Candidate& out) const {
    const int ka = (k + 1) % 3, kb = (k + 2) % 3;
    const u32 f = r.f, v = r.v[k], a = r.v[ka], b = r.v[kb], h = r.n[k], t = r.n[kb];
    if (h < f || t < f || r.j[k] < 0) return false;
    int hv = -1, tv = -1;
    for (int s = 0; s < 3; ++s) {
      if (r.gv[k][s] == v) hv = s;
      if (r.gv[kb][s] == v) tv = s;
    }
    if (hv < 0 || tv < 0) return false;
    const u32 d = r.gv[k][(hv + 1) % 3];
    if (r.gv[k][(hv + 2) % 3] != a || r.gv[kb][(tv + 1) % 3] != b || r.gv[kb][(tv + 2) % 3] != d)
      return false;
    if (r.gn[k][hv] != t || r.gn[kb][tv] != f) return false;  // degree above 3
    const Vec3d &pv = r.p[k], &pa = r.p[ka], &pb = r.p[kb], &pd = r.y[k];
    if (orient3d(pa, pb, pd, pv) > 0) return false;  // v is strictly extreme here
    const u32 ab = r.n[ka], da = r.gn[k][(hv + 1) % 3], bd = r.gn[kb][(tv + 1) % 3];
    if (orient3d(m.c, pa, pb, pd) <= 0 || ab == da || ab == bd || da == bd || ab == h || ab == t || da == f ||
        da == t || bd == f || bd == h) {
      log.add(kRejectRemoval, 6 * f + 3 + static_cast<u32>(k), v, a, b, d);
      return false;
    }
    out = Candidate{kRemoval, 0, {f, h, t, ab, bd, da}, {v, a, b, d}};
    return true;
  }

  // The first candidate of face f: its three edges, then its three corners.  slot receives 0..5.  (Two
  // loops of three, which unroll: one loop over the six slots made the rounds slower (docs/benchmarks.md,
  // "Measurements behind the code").)  kCompact: the loops stay loops, a third of their code (the batch
  // kernel, whose blocks run different phases at once and wait on the instruction cache).
  template <bool kCompact = false>
  CUDAHULL_HD bool first(u32 f, Candidate& out, int& slot) const {
    [[maybe_unused]] constexpr int kUnroll = kCompact ? 1 : 3;
    Around<Point> around;
    around.gather(m, f);
#if defined(__CUDA_ARCH__)
#pragma unroll(kUnroll)
#endif
    for (int i = 0; i < 3; ++i) {
      if (swap(around, i, out)) {
        slot = i;
        return true;
      }
    }
#if defined(__CUDA_ARCH__)
#pragma unroll(kUnroll)
#endif
    for (int k = 0; k < 3; ++k) {
      if (removal(around, k, out)) {
        slot = 3 + k;
        return true;
      }
    }
    return false;
  }
};

// The faces round `round` looks at: live ones made in the previous round (id >= fresh_from), and those
// stamped for it (revisit[f] == round): the faces next to the previous round's new ones (the lower face of an
// edge owns it, and a removal belongs to the lowest of three faces), and those whose candidate lost a claim.
template <class Point>
struct MarkWork {
  MeshView<Point> m;
  const u32* revisit;
  u32 fresh_from, round;
  CUDAHULL_HD bool is_work(u32 f) const {
    return m.replaced_by[f] == kAlive && (f >= fresh_from || revisit[f] == round);
  }
};

// A work face's links to faces the previous round killed, pointed at the new faces that hold the edges
// (the entry of the edit that killed them names those).  Every face writes only its own links.
template <class Point>
struct FixLinks {
  MeshView<Point> m;
  CUDAHULL_HD void fix(u32 f) const {
    for (int k = 0; k < 3; ++k) {
      const u32 nb = m.fn[3 * f + k], e = m.replaced_by[nb];
      if (e == kAlive) continue;
      const Entry& entry = m.entries[e];
      const u32 a = m.fv[3 * f + k], b = m.fv[3 * f + (k + 1) % 3];
      for (int o = 0; o < (entry.kind == kSwap ? 2 : 1); ++o) {
        if (m.edge_slot(entry.out[o], b, a) >= 0) m.fn[3 * f + k] = entry.out[o];
      }
    }
  }
};

// Each work face finds its first candidate, keeps it, and claims the candidate's faces (kCompact: as
// FindCandidate::first's).
template <class Point, class Find = FindCandidate<Point>, bool kCompact = false>
struct Claim {
  Find find;
  u32 round;
  u64* claim;
  u32* revisit;
  CUDAHULL_HD void claim_for(u32 f, Candidate& cand) const {
    int slot = 0;
    if (!find.template first<kCompact>(f, cand, slot)) {
      cand.kind = kNone;
      return;
    }
    take(f, cand, slot);
  }
  // Face f's first candidate, found at `slot`: kept, and its faces claimed.
  CUDAHULL_HD void take(u32 f, Candidate& cand, int slot) const {
    revisit[f] = round + 1;  // won (then killed) or lost (then tried again)
    cand.id = 6 * f + static_cast<u32>(slot);
    const u64 key = claim_key(round, cand.id);
    for (u32 k = 0; k < claimed_faces(cand); ++k)
      atomic_max_u64(&claim[cand.faces[k]], key);
  }
};

// Did the work item's candidate hold all its claims?
struct Won {
  u32 round;
  const u64* claim;
  CUDAHULL_HD bool holds(const Candidate& cand) const {
    if (cand.kind == kNone) return false;
    const u64 key = claim_key(round, cand.id);
    for (u32 k = 0; k < claimed_faces(cand); ++k) {
      if (claim[cand.faces[k]] != key) return false;
    }
    return true;
  }
};

// The winners apply: two new face slots and one entry each, by their rank in face order; each rewrites
// only the faces it claimed and its new ones (and stamps the faces around).
template <class Point>
struct Apply {
  MeshView<Point> m;
  u32 first_face, first_entry;
  u32* revisit;
  u32 round;

  // An outer face: it links to a face killed here until FixLinks, in the next round, points it at the new
  // one (another winner may be killing it this round).  Every winner that touches it writes the same stamp.
  CUDAHULL_HD void touch(u32 face) const { revisit[face] = round + 1; }
  CUDAHULL_HD void set_face(u32 f, u32 a, u32 b, u32 d, u32 na, u32 nb, u32 nd) const {
    u32* fv = m.fv + 3 * f;
    u32* fn = m.fn + 3 * f;
    fv[0] = a, fv[1] = b, fv[2] = d;
    fn[0] = na, fn[1] = nb, fn[2] = nd;
    m.replaced_by[f] = kAlive;
    revisit[f] = 0;
  }
  // A winning candidate, the r-th winner of its round.
  CUDAHULL_HD void apply(const Candidate& cand, u32 r) const {
    const u32 n1 = first_face + 2 * r, n2 = n1 + 1, e = first_entry + r;
    if (cand.kind == kSwap) {
      const u32 u = cand.vertex[0], v = cand.vertex[1], x = cand.vertex[2], y = cand.vertex[3];
      const u32 A = cand.faces[2], B = cand.faces[3], C = cand.faces[4], D = cand.faces[5];
      set_face(n1, x, u, y, A, B, n2);
      set_face(n2, y, v, x, C, D, n1);
      touch(A);
      touch(B);
      touch(C);
      touch(D);
      m.entries[e] = Entry{kSwap, x, y, {n1, n2, kNone}};
      m.replaced_by[cand.faces[0]] = e;
      m.replaced_by[cand.faces[1]] = e;
    } else {
      const u32 a = cand.vertex[1], b = cand.vertex[2], d = cand.vertex[3];
      const u32 ab = cand.faces[3], bd = cand.faces[4], da = cand.faces[5];
      set_face(n1, a, b, d, ab, bd, da);
      touch(ab);
      touch(bd);
      touch(da);
      m.replaced_by[n2] = kDeadSlot;
      for (int k = 0; k < 3; ++k)
        m.fv[3 * n2 + k] = m.fn[3 * n2 + k] = kNone;
      revisit[n2] = 0;
      m.entries[e] = Entry{kRemoval, kNone, kNone, {n1, kNone, kNone}};
      for (int k = 0; k < 3; ++k)
        m.replaced_by[cand.faces[k]] = e;
    }
  }
};

// The state of the iteration's launches (iteration.hpp) and of their rounds: what the host reads after a
// launch.  The rounds stop when no candidate is left, or when a round's winners would not fit the
// capacities, before they apply (overflow: the round's work stamped back, the host grows the buffers and
// the round runs again, with the same claims and winners).
//   The state stays where the executor computes for the whole run, and the host reads it once a launch:
//   the phases take their counts from it (refined, faces, entries), not from the host.  The counters
//   (rounds, edits, work_items, phase_ns) add up over the run.
struct RoundsState {
  u32 faces, fresh_from, entries, round;    // faces and entries in use; faces from fresh_from are new
  u32 face_capacity, entry_capacity;        // set at each launch
  u32 work_capacity;                        // set at each launch: the work items a round has room for
  u32 rounds, edits, work_items, overflow;  // out
  u32 needed_faces, needed_entries;         // out, on overflow: what the next round needs
  u32 needed_rejections, needed_rounds;     // out, on overflow of a recording run's log (RejectionLog)
  u32 needed_work;                          // out, on overflow: the work items of the round
  u32 round_work, round_winners;            // scratch, zero
  u32 refined;                              // faces refined this iteration (SplitFaces)
  u32 live_faces, kept_points;              // the compaction's totals (MoveLive, MovePoints)
  // A launch of the iteration's phases (iteration.hpp): the iterations it finished, the faces it refined,
  // and why it stopped (IterationExit).
  u32 loop_iterations, loop_refined, loop_exit;
  u32 faults, vertices;  // the finish's counts: edges not strictly convex (CountFaults), hull vertices
  u32 defects;           // concave edges and thin vertices (CountConcave, CountThin)
  u64 phase_ns[4];       // out, device only: claim, judge, number, apply (profiling)
};

// What a run of rounds starts from: `begin` (the iteration's first: faces = fresh_from + 3 refined,
// entries = refined, from the state) or not (it goes on after an overflow), and the room there is.
struct RoundsLaunch {
  u32 begin, fresh_from, face_capacity, entry_capacity, work_capacity;
};

// A run of rounds starts (one thread): the iteration's counts from the refinement's, or those the last
// run stopped at; the room there is; no overflow, and no work listed yet (a run that overflowed left its
// count).
CUDAHULL_HD inline void start_rounds(RoundsState* st, const RoundsLaunch& launch) {
  if (launch.begin) {
    st->fresh_from = launch.fresh_from;
    st->faces = launch.fresh_from + 3 * st->refined;
    st->entries = st->refined;
  }
  st->face_capacity = launch.face_capacity;
  st->entry_capacity = launch.entry_capacity;
  st->work_capacity = launch.work_capacity;
  st->overflow = 0;
  st->round_work = 0;
  // What an overflow asks for is set by the overflow: none is left from an earlier one.
  st->needed_faces = st->needed_entries = st->needed_rejections = st->needed_rounds = st->needed_work = 0;
}

}  // namespace cudahull::resident
