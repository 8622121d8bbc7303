#include "cudahull/mesh.hpp"

#include <algorithm>
#include <atomic>
#include <stdexcept>

#include "cudahull/parallel.hpp"

namespace cudahull {

namespace {
int next(int i) {
  return i == 2 ? 0 : i + 1;
}
int prev(int i) {
  return i == 0 ? 2 : i - 1;
}
}  // namespace

FaceId Mesh::add_face(PointIndex a, PointIndex b, PointIndex c) {
  FaceId id = static_cast<FaceId>(faces_.size());
  MeshFace face;
  face.v = {a, b, c};
  faces_.push_back(face);
  alive_.push_back(1);
  ++live_count_;
  for (PointIndex p : {a, b, c}) {
    FaceId& slot = vertex_face_[p];
    if (slot == 0) ++vertex_count_;
    slot = id + 1;
  }
  return id;
}

void Mesh::assign(const std::vector<MeshFace>& faces) {
  faces_.clear();
  alive_.clear();
  live_count_ = 0;
  vertex_face_.clear();
  vertex_count_ = 0;
  faces_.reserve(faces.size());
  alive_.reserve(faces.size());
  vertex_face_.reserve(faces.size() / 2 + 2);  // a closed triangulation: V = F / 2 + 2
  for (const MeshFace& face : faces) {
    const FaceId id = add_face(face.v[0], face.v[1], face.v[2]);
    faces_[id].n = face.n;
  }
}

void Mesh::kill(FaceId f) {
  alive_[f] = 0;
  --live_count_;
}

void Mesh::make_tetrahedron(PointIndex p0, PointIndex p1, PointIndex p2, PointIndex p3) {
  faces_.clear();
  alive_.clear();
  live_count_ = 0;
  vertex_face_.clear();
  vertex_count_ = 0;
  // p3 lies below (p0, p1, p2), so that triangle already faces outward; the other three are oriented to
  // match, each edge appearing once in each direction.
  FaceId f0 = add_face(p0, p1, p2);
  FaceId f1 = add_face(p1, p0, p3);
  FaceId f2 = add_face(p2, p1, p3);
  FaceId f3 = add_face(p0, p2, p3);
  auto link_all = [&](FaceId f) {
    for (int i = 0; i < 3; ++i) {
      PointIndex a = faces_[f].v[i], b = faces_[f].v[next(i)];
      for (FaceId g : {f0, f1, f2, f3}) {
        if (g != f && edge_index(g, b, a) >= 0) faces_[f].n[i] = g;
      }
    }
  };
  for (FaceId f : {f0, f1, f2, f3})
    link_all(f);
}

std::vector<PointIndex> Mesh::vertices() const {
  std::vector<PointIndex> out;
  out.reserve(vertex_count_);
  vertex_face_.for_each([&](PointIndex v, FaceId slot) {
    if (slot != 0) out.push_back(v);
  });
  parallel_sort(out);
  return out;
}

int Mesh::edge_index(FaceId f, PointIndex a, PointIndex b) const {
  const MeshFace& face = faces_[f];
  for (int i = 0; i < 3; ++i) {
    if (face.v[i] == a && face.v[next(i)] == b) return i;
  }
  return -1;
}

void Mesh::relink(FaceId g, PointIndex a, PointIndex b, FaceId to) {
  int j = edge_index(g, a, b);
  if (j < 0) throw std::logic_error("mesh adjacency is inconsistent");
  faces_[g].n[j] = to;
}

std::array<FaceId, 3> Mesh::split(FaceId f, PointIndex p) {
  const MeshFace old = faces_[f];
  const PointIndex a = old.v[0], b = old.v[1], c = old.v[2];
  kill(f);
  FaceId c0 = add_face(a, b, p), c1 = add_face(b, c, p), c2 = add_face(c, a, p);
  faces_[c0].n = {old.n[0], c1, c2};
  faces_[c1].n = {old.n[1], c2, c0};
  faces_[c2].n = {old.n[2], c0, c1};
  relink(old.n[0], b, a, c0);
  relink(old.n[1], c, b, c1);
  relink(old.n[2], a, c, c2);
  return {c0, c1, c2};
}

Mesh::SwapQuad Mesh::swap_quad(FaceId f, int i) const {
  const MeshFace& ff = faces_[f];
  SwapQuad q;
  q.f = f;
  q.g = ff.n[i];
  q.u = ff.v[i], q.v = ff.v[next(i)], q.x = ff.v[prev(i)];
  const int j = edge_index(q.g, q.v, q.u);
  if (j < 0) throw std::logic_error("mesh adjacency is inconsistent");
  const MeshFace& gg = faces_[q.g];
  q.y = gg.v[prev(j)];
  q.across_vx = ff.n[next(i)], q.across_xu = ff.n[prev(i)];
  q.across_uy = gg.n[next(j)], q.across_yv = gg.n[prev(j)];
  return q;
}

void Mesh::make_swapped_faces(const SwapQuad& q, FaceId n1, FaceId n2) {
  faces_[n1].v = {q.x, q.u, q.y};
  faces_[n1].n = {q.across_xu, q.across_uy, n2};
  faces_[n2].v = {q.y, q.v, q.x};
  faces_[n2].n = {q.across_yv, q.across_vx, n1};
}

std::array<FaceId, 2> Mesh::swap(FaceId f, int i) {
  const SwapQuad q = swap_quad(f, i);
  kill(q.f);
  kill(q.g);
  const FaceId n1 = add_face(q.x, q.u, q.y), n2 = add_face(q.y, q.v, q.x);
  make_swapped_faces(q, n1, n2);
  relink(q.across_xu, q.u, q.x, n1);
  relink(q.across_uy, q.y, q.u, n1);
  relink(q.across_yv, q.v, q.y, n2);
  relink(q.across_vx, q.x, q.v, n2);
  return {n1, n2};
}

FaceId Mesh::split_batch(const std::vector<FaceId>& faces, const std::vector<PointIndex>& apexes,
                         unsigned workers) {
  const std::size_t count = faces.size();
  const FaceId first = static_cast<FaceId>(faces_.size());
  split_of_.assign(faces_.size(), -1);
  for (std::size_t k = 0; k < count; ++k)
    split_of_[faces[k]] = static_cast<std::int32_t>(k);
  // The apexes are new keys of the vertex map: insert them here, before the threads look keys up.  Each
  // ends on its last child, as add_face() leaves it.
  vertex_face_.reserve(vertex_count_ + count);
  for (std::size_t k = 0; k < count; ++k) {
    FaceId& slot = vertex_face_[apexes[k]];
    if (slot == 0) ++vertex_count_;
    slot = first + 3 * static_cast<FaceId>(k) + 2 + 1;
  }
  faces_.resize(faces_.size() + 3 * count);
  alive_.resize(alive_.size() + 3 * count, 1);
  live_count_ += 2 * count;
  parallel_chunks(
      count, workers,
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < end; ++k) {
          // Refined faces are only read here; an unrefined neighbour's slot for the shared edge has one
          // writer, the child that takes that edge.
          const FaceId f = faces[k];
          const MeshFace& old = faces_[f];
          const FaceId child = first + 3 * static_cast<FaceId>(k);
          for (int i = 0; i < 3; ++i) {
            const PointIndex a = old.v[i], b = old.v[next(i)];
            const FaceId g = old.n[i];
            FaceId across = g;
            const int j = edge_index(g, b, a);
            if (j < 0) throw std::logic_error("mesh adjacency is inconsistent");
            if (split_of_[g] >= 0) {
              across = first + 3 * static_cast<FaceId>(split_of_[g]) + static_cast<FaceId>(j);
            } else {
              faces_[g].n[j] = child + static_cast<FaceId>(i);
            }
            MeshFace& made = faces_[child + static_cast<FaceId>(i)];
            made.v = {a, b, apexes[k]};
            made.n = {across, child + static_cast<FaceId>(next(i)), child + static_cast<FaceId>(prev(i))};
          }
          // Old corner i ends on the last child that holds it: child 2 for corners 0 and 2, child 1 for 1.
          const FaceId last_child[3] = {child + 2, child + 1, child + 2};
          for (int i = 0; i < 3; ++i) {
            std::atomic_ref<FaceId> slot(*vertex_face_.find(old.v[i]));
            FaceId held = slot.load(std::memory_order_relaxed);
            while (held < last_child[i] + 1 &&
                   !slot.compare_exchange_weak(held, last_child[i] + 1, std::memory_order_relaxed)) {
            }
          }
        }
      },
      1024);
  for (FaceId f : faces)
    alive_[f] = 0;
  return first;
}

FaceId Mesh::swap_batch(const std::vector<std::pair<FaceId, int>>& swaps, unsigned workers) {
  // Each swap as swap() sees it, read before any is made.
  const std::size_t count = swaps.size();
  std::vector<SwapQuad> quads(count);
  parallel_chunks(
      count, workers,
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < end; ++k)
          quads[k] = swap_quad(swaps[k].first, swaps[k].second);
      },
      1024);
  // Make the new faces, linked to the old outer faces for now, and kill the old ones.
  const FaceId first = static_cast<FaceId>(faces_.size());
  faces_.resize(faces_.size() + 2 * count);
  alive_.resize(alive_.size() + 2 * count, 1);
  if (dead_into_.size() < first) dead_into_.resize(first);
  parallel_chunks(
      count, workers,
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < end; ++k) {
          const SwapQuad& q = quads[k];
          const FaceId n1 = first + 2 * static_cast<FaceId>(k), n2 = n1 + 1;
          make_swapped_faces(q, n1, n2);
          alive_[q.f] = 0;
          alive_[q.g] = 0;
          dead_into_[q.f] = n1;
          dead_into_[q.g] = n1;
          // As add_face() in order would leave it: the last new face that holds the vertex (swaps that share
          // a vertex race here, and the highest id wins whatever the thread timing).
          auto raise = [&](PointIndex p, FaceId face) {
            std::atomic_ref<FaceId> slot(*vertex_face_.find(p));
            FaceId held = slot.load(std::memory_order_relaxed);
            while (held < face + 1 &&
                   !slot.compare_exchange_weak(held, face + 1, std::memory_order_relaxed)) {
            }
          };
          raise(q.u, n1);
          raise(q.v, n2);
          raise(q.x, n2);
          raise(q.y, n2);
        }
      },
      1024);
  // An outer face that another swap of the batch killed was replaced by one of that swap's two faces: the
  // one with the reversed edge.  A live outer face points back at the new face (one writer per edge).
  parallel_chunks(
      2 * count, workers,
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t k = begin; k < end; ++k) {
          const FaceId face = first + static_cast<FaceId>(k);
          MeshFace& made = faces_[face];
          for (int e = 0; e < 2; ++e) {
            const PointIndex a = made.v[e], b = made.v[next(e)];
            FaceId& across = made.n[e];
            if (alive_[across]) {
              faces_[across].n[edge_index(across, b, a)] = face;
            } else {
              const FaceId other = dead_into_[across];
              across = edge_index(other, b, a) >= 0 ? other : other + 1;
            }
          }
        }
      },
      1024);
  return first;
}

// Calls visit(face, k) for each face around v, counter-clockwise from outside (v == face.v[k]), until it
// returns false.  Every walk around a vertex goes through here.
template <class Visit>
void Mesh::walk_around(PointIndex v, Visit&& visit) const {
  if (!has_vertex(v)) return;
  const FaceId start = face_of_vertex(v);
  FaceId f = start;
  std::size_t steps = 0;
  do {
    const MeshFace& face = faces_[f];
    int k = 0;
    while (face.v[k] != v)
      ++k;
    if (!visit(f, k)) return;
    f = face.n[prev(k)];  // across the edge v[k+2] -> v: the next face counter-clockwise around v
    if (++steps > faces_.size()) throw std::logic_error("mesh ring does not close");
  } while (f != start);
}

void Mesh::ring(PointIndex v, std::vector<PointIndex>& ring_vertices, std::vector<FaceId>& ring_faces) const {
  ring_vertices.clear();
  ring_faces.clear();
  walk_around(v, [&](FaceId f, int k) {
    ring_vertices.push_back(faces_[f].v[next(k)]);
    ring_faces.push_back(f);
    return true;
  });
}

bool Mesh::adjacent(PointIndex a, PointIndex b) const {
  bool found = false;
  walk_around(a, [&](FaceId f, int k) { return !(found = faces_[f].v[next(k)] == b); });
  return found;
}

std::size_t Mesh::degree(PointIndex v, std::size_t limit) const {
  std::size_t count = 0;
  walk_around(v, [&](FaceId, int) { return ++count < limit; });
  return count;
}

FaceId Mesh::remove_degree3(PointIndex v) {
  std::vector<PointIndex> rv;
  std::vector<FaceId> rf;
  ring(v, rv, rf);
  if (rv.size() != 3) throw std::logic_error("remove_degree3 on a vertex of degree != 3");
  const PointIndex a = rv[0], b = rv[1], d = rv[2];
  // Face rf[k] = (v, ring[k], ring[k+1]); its outer edge ring[k] -> ring[k+1] keeps its neighbour.
  FaceId outer[3];
  for (int k = 0; k < 3; ++k) {
    const MeshFace& face = faces_[rf[k]];
    outer[k] = face.n[edge_index(rf[k], rv[k], rv[(k + 1) % 3])];
  }
  for (FaceId f : rf)
    kill(f);
  vertex_face_[v] = 0;
  --vertex_count_;
  FaceId n = add_face(a, b, d);
  faces_[n].n = {outer[0], outer[1], outer[2]};
  relink(outer[0], b, a, n);
  relink(outer[1], d, b, n);
  relink(outer[2], a, d, n);
  return n;
}

const std::vector<FaceId>& Mesh::compact() {
  // Into a second buffer that keeps its capacity (fresh arrays of millions of faces would cost page faults
  // every iteration), on all cores: new ids by a prefix count per chunk, then the copy.
  const std::size_t capacity = faces_.size();
  const unsigned workers = hardware_workers();
  const std::size_t chunk = (capacity + workers - 1) / workers;
  std::vector<FaceId> chunk_base(workers + 1, 0);
  remap_.resize(capacity);
  parallel_chunks(
      workers, workers,
      [&](std::size_t wb, std::size_t we, unsigned) {
        for (std::size_t w = wb; w < we; ++w) {
          FaceId live = 0;
          for (std::size_t f = w * chunk; f < std::min(capacity, (w + 1) * chunk); ++f)
            live += alive_[f];
          chunk_base[w + 1] = live;
        }
      },
      capacity < 65536 ? workers + 1 : 1);
  for (unsigned w = 0; w < workers; ++w)
    chunk_base[w + 1] += chunk_base[w];
  const FaceId live = chunk_base[workers];
  if (live > compacted_.capacity()) {  // grown without copying what it held: every face is written below
    std::vector<MeshFace> grown;
    grown.reserve(2 * live);  // only address space until written
    compacted_.swap(grown);
  }
  compacted_.resize(live);
  parallel_chunks(
      workers, workers,
      [&](std::size_t wb, std::size_t we, unsigned) {
        for (std::size_t w = wb; w < we; ++w) {
          FaceId next_id = chunk_base[w];
          for (std::size_t f = w * chunk; f < std::min(capacity, (w + 1) * chunk); ++f)
            remap_[f] = alive_[f] ? next_id++ : kNoFace;
        }
      },
      capacity < 65536 ? workers + 1 : 1);
  parallel_chunks(
      capacity, workers,
      [&](std::size_t begin, std::size_t end, unsigned) {
        for (std::size_t f = begin; f < end; ++f) {
          if (!alive_[f]) continue;
          MeshFace& kept = compacted_[remap_[f]];
          kept = faces_[f];
          for (FaceId& nb : kept.n)
            nb = remap_[nb];
        }
      },
      65536);
  faces_.swap(compacted_);
  alive_.assign(live, 1);
  live_count_ = live;
  // Each vertex's face is live (add_face sets it for every corner of every new face, and only a removed
  // vertex loses all its faces), so renumbering it is enough.
  parallel_chunks(
      vertex_face_.slot_count(), workers,
      [&](std::size_t begin, std::size_t end, unsigned) {
        vertex_face_.for_each_in(begin, end, [&](PointIndex, FaceId& slot) {
          if (slot != 0) slot = remap_[slot - 1] + 1;
        });
      },
      65536);
  return remap_;
}

}  // namespace cudahull
