// planar_candidates(): the 2-D hull's filter on the device (design in planar_filter.hpp).
#include "cudahull/cuda/planar_filter.hpp"

#include <cuda_runtime.h>

#include <thrust/iterator/counting_iterator.h>
#include <algorithm>
#include <cmath>
#include <cub/device/device_select.cuh>
#include <type_traits>

#include "cuda_errors.hpp"
#include "cudahull/cuda/device_memory.hpp"
#include "cudahull/cuda/device_points.hpp"
#include "cudahull/predicates.hpp"

namespace cudahull {

namespace {

constexpr const char* kWho = "2-D filter";
constexpr unsigned kThreads = 256;
constexpr int kDirections = 16;  // each searched both ways: 32 extremes
constexpr int kExtremes = 2 * kDirections;

// The inner polygon, counter-clockwise, passed by value to the selection (not in __constant__ memory: two
// host threads filtering at once would overwrite each other's).
struct InnerPolygon {
  double corner[kExtremes][2];
  int corners;
};

constexpr CudaCheck check{kWho};

// in_fast_exact_range() (predicates.hpp) for double: one outside it goes to the host's wide-range path;
// a float is finite or not.
template <class Scalar>
__device__ bool acceptable(Scalar c) {
  const double v = static_cast<double>(c);
  if (!isfinite(v)) return false;
  if constexpr (std::is_same_v<Scalar, double>) {
    return in_fast_exact_range(v);
  }
  return true;
}

// A key that orders like the value (rounded to float: the extremes need no exactness), with the index in
// its low half, so that one 64-bit atomicMax keeps a point of (nearly) greatest value.
__device__ unsigned long long extreme_key(double value, unsigned index) {
  const unsigned bits = __float_as_uint(__double2float_rn(value));
  const unsigned ordered = (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
  return (static_cast<unsigned long long>(ordered) << 32) | index;
}

template <class Scalar>
__global__ void check_and_find_extremes(const Scalar* xy, std::size_t count, unsigned long long* keys,
                                        unsigned long long* first_bad) {
  // The directions k pi / kDirections, and point 0 as the origin the values are taken from, so that a cloud
  // far from the origin (UTM coordinates, say) still spreads its keys over many floats.
  double directions[kDirections][2];
  for (int d = 0; d < kDirections; ++d)
    sincospi(static_cast<double>(d) / kDirections, &directions[d][1], &directions[d][0]);
  const double ox = static_cast<double>(xy[0]), oy = static_cast<double>(xy[1]);
  const bool from_origin = !(isfinite(ox) && isfinite(oy));
  unsigned long long best[kExtremes];
  for (int k = 0; k < kExtremes; ++k)
    best[k] = 0;
  const std::size_t stride = static_cast<std::size_t>(gridDim.x) * blockDim.x;
  for (std::size_t i = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x; i < count;
       i += stride) {
    const Scalar x = xy[2 * i], y = xy[2 * i + 1];
    if (!acceptable(x) || !acceptable(y)) {
      atomicMin(first_bad, static_cast<unsigned long long>(i));
      continue;
    }
    const double rx = from_origin ? static_cast<double>(x) : static_cast<double>(x) - ox;
    const double ry = from_origin ? static_cast<double>(y) : static_cast<double>(y) - oy;
    for (int d = 0; d < kDirections; ++d) {
      const double along = rx * directions[d][0] + ry * directions[d][1];
      best[2 * d] = max(best[2 * d], extreme_key(along, static_cast<unsigned>(i)));
      best[2 * d + 1] = max(best[2 * d + 1], extreme_key(-along, static_cast<unsigned>(i)));
    }
  }
  for (int k = 0; k < kExtremes; ++k) {
    unsigned long long v = best[k];
    for (int offset = 16; offset > 0; offset /= 2)
      v = max(v, __shfl_xor_sync(0xffffffffu, v, offset));
    if ((threadIdx.x & 31) == 0 && v != 0) atomicMax(&keys[k], v);
  }
}

// Keeps a point unless it is strictly inside the inner polygon (strictly left of every edge, exactly).
template <class Scalar>
struct NotStrictlyInside {
  const Scalar* xy;
  InnerPolygon inner;
  __device__ bool operator()(unsigned i) const {
    const double x = xy[2 * static_cast<std::size_t>(i)], y = xy[2 * static_cast<std::size_t>(i) + 1];
    for (int k = 0; k < inner.corners; ++k) {
      const int next = k + 1 == inner.corners ? 0 : k + 1;
      const double(&a)[2] = inner.corner[k];
      const double(&b)[2] = inner.corner[next];
      if (orient2d(a[0], a[1], b[0], b[1], x, y) <= 0) return true;
    }
    return false;
  }
};

// The extremes' coordinates, beside their keys, so that one read brings both (a key of 0: no point).
template <class Scalar>
__global__ void extreme_points(const Scalar* xy, const unsigned long long* keys, double* out) {
  const int k = threadIdx.x;
  if (k >= kExtremes) return;
  const std::size_t i = static_cast<std::uint32_t>(keys[k]);
  out[2 * k] = keys[k] ? static_cast<double>(xy[2 * i]) : 0;
  out[2 * k + 1] = keys[k] ? static_cast<double>(xy[2 * i + 1]) : 0;
}

template <class Scalar>
__global__ void gather(const Scalar* xy, const unsigned* indices, unsigned count, Scalar* out) {
  for (unsigned k = blockIdx.x * blockDim.x + threadIdx.x; k < count; k += gridDim.x * blockDim.x) {
    out[2 * k] = xy[2 * static_cast<std::size_t>(indices[k])];
    out[2 * k + 1] = xy[2 * static_cast<std::size_t>(indices[k]) + 1];
  }
}

unsigned grid_for(std::size_t count) {
  return grid_stride_blocks(count, kThreads, 8);
}

struct Corner {
  double x, y;
};

// The strict corners of a few points' hull, counter-clockwise (Andrew's monotone chain, exact orient2d).
std::vector<Corner> small_hull(std::vector<Corner> p) {
  std::sort(p.begin(), p.end(),
            [](const Corner& a, const Corner& b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
  p.erase(std::unique(p.begin(), p.end(),
                      [](const Corner& a, const Corner& b) { return a.x == b.x && a.y == b.y; }),
          p.end());
  if (p.size() < 3) return p;
  std::vector<Corner> hull(2 * p.size());
  std::size_t k = 0;
  auto turn = [&](const Corner& a, const Corner& b, const Corner& c) {
    return orient2d(a.x, a.y, b.x, b.y, c.x, c.y);
  };
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], p[i]) <= 0)
      --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(hull[k - 2], hull[k - 1], p[i]) <= 0)
      --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);
  return hull;
}

}  // namespace

template <class Scalar>
PlanarCandidates<Scalar> planar_candidates(const Scalar* xy, std::size_t count) {
  PlanarCandidates<Scalar> out;
  out.first_bad = count;
  if (count == 0) return out;
  check(cudaDeviceSynchronize(), "waiting for the points' producer");
  const TrimPoolAtEnd trim;  // after the arrays below

  // One pass: the check and the extremes; their coordinates beside them; one read of all.
  struct Found {
    unsigned long long keys[kExtremes];
    unsigned long long first_bad;
    double xy[kExtremes][2];
  };
  const DeviceArray<Found> scratch(1, kWho, "the extremes");
  Found found{};
  found.first_bad = count;
  check(cudaMemcpy(scratch.get(), &found, sizeof found, cudaMemcpyHostToDevice), "clearing the extremes");
  check_and_find_extremes<<<grid_for(count), kThreads>>>(xy, count, scratch.get()->keys,
                                                         &scratch.get()->first_bad);
  check(cudaGetLastError(), "launching the extremes' search");
  extreme_points<<<1, kExtremes>>>(xy, scratch.get()->keys, &scratch.get()->xy[0][0]);
  check(cudaGetLastError(), "launching the extremes' read");
  check(cudaMemcpy(&found, scratch.get(), sizeof found, cudaMemcpyDeviceToHost), "reading the extremes");
  out.host_syncs += 1;
  out.bytes_from_device += sizeof found;
  out.first_bad = static_cast<std::size_t>(found.first_bad);
  if (out.first_bad != count) return out;

  std::vector<Corner> extremes;
  for (int k = 0; k < kExtremes; ++k) {
    if (found.keys[k] != 0) extremes.push_back({found.xy[k][0], found.xy[k][1]});
  }
  const std::vector<Corner> polygon = small_hull(extremes);
  if (polygon.size() < 3) {
    out.degenerate = true;
    return out;
  }
  NotStrictlyInside<Scalar> keep{xy, {}};
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    keep.inner.corner[k][0] = polygon[k].x;
    keep.inner.corner[k][1] = polygon[k].y;
  }
  keep.inner.corners = static_cast<int>(polygon.size());

  // The survivors, in input order (DeviceSelect is stable), then their coordinates, gathered into a buffer
  // of their number only.
  const DeviceArray<unsigned> indices(count, kWho, "the survivors' indices");
  const DeviceArray<std::int64_t> selected(1, kWho, "the survivors' count");
  thrust::counting_iterator<unsigned> all(0);
  std::size_t temp_bytes = 0;
  const auto items = static_cast<std::int64_t>(count);
  check(cub::DeviceSelect::If(nullptr, temp_bytes, all, indices.get(), selected.get(), items, keep),
        "sizing the selection");
  const DeviceArray<unsigned char> temp(temp_bytes, kWho, "the selection's scratch");
  check(cub::DeviceSelect::If(temp.get(), temp_bytes, all, indices.get(), selected.get(), items, keep),
        "selecting the survivors");
  std::int64_t selected_count = 0;
  check(cudaMemcpy(&selected_count, selected.get(), sizeof selected_count, cudaMemcpyDeviceToHost),
        "reading the count");
  const auto survivors = static_cast<unsigned>(selected_count);
  const DeviceArray<Scalar> coordinates(2 * static_cast<std::size_t>(survivors), kWho,
                                        "the survivors' coordinates");
  gather<<<grid_for(survivors), kThreads>>>(xy, indices.get(), survivors, coordinates.get());
  check(cudaGetLastError(), "launching the gather");
  out.indices.resize(survivors);
  out.xy.resize(2 * static_cast<std::size_t>(survivors));
  check(cudaMemcpy(out.indices.data(), indices.get(), survivors * sizeof(unsigned), cudaMemcpyDeviceToHost),
        "reading the survivors");
  check(cudaMemcpy(out.xy.data(), coordinates.get(), 2 * static_cast<std::size_t>(survivors) * sizeof(Scalar),
                   cudaMemcpyDeviceToHost),
        "reading the survivors' coordinates");
  out.host_syncs += 3;
  out.bytes_from_device += sizeof selected_count + survivors * (sizeof(unsigned) + 2 * sizeof(Scalar));
  return out;
}

template <class Scalar>
std::array<double, 3> read_device_point_2d(const Scalar* xy, std::size_t index) {
  Scalar p[2];
  check(cudaMemcpy(p, xy + 2 * index, sizeof p, cudaMemcpyDeviceToHost), "reading a point");
  return {static_cast<double>(p[0]), static_cast<double>(p[1]), 0};
}

template std::array<double, 3> read_device_point_2d(const float*, std::size_t);
template std::array<double, 3> read_device_point_2d(const double*, std::size_t);
template PlanarCandidates<float> planar_candidates(const float*, std::size_t);
template PlanarCandidates<double> planar_candidates(const double*, std::size_t);

}  // namespace cudahull
