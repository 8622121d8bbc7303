// The describe of a batch's hulls on the device (describe_batch_cuda(), batch_cuda.hpp): a warp a done
// cloud, into the packed result's columns (batch_cuda.cu's design, "describe").
#include <cuda_runtime.h>

#include <cstdint>

#include "batch_shared.cuh"
#include "cudahull/cuda/batch_cuda.hpp"
#include "cudahull/detail/plane_impl.hpp"

namespace cudahull {
namespace {

// The describe (describe_batch_cuda()): a warp a done cloud of a pass.
template <class Point>
struct DescribeArgs {
  const u32* words;          // the pass's output: per cloud 3 corners a face (into its vertex list), the list
  const Point* coordinates;  // per cloud its vertices', in the list's order
  const BatchResult* results;
  const u32* clouds;  // the pass's clouds, as listed
  u32 listed;
  BatchColumns columns;
};

constexpr int kDescribeThreads = 128;

template <class Point>
__global__ void __launch_bounds__(kDescribeThreads) describe_kernel(DescribeArgs<Point> a) {
  const u32 lane = threadIdx.x % 32, warps = gridDim.x * (kDescribeThreads / 32);
  for (u32 k = blockIdx.x * (kDescribeThreads / 32) + threadIdx.x / 32; k < a.listed; k += warps) {
    const BatchResult r = a.results[k];
    if (r.status != resident::kBatchDone) continue;
    const u32 c = a.clouds[k];
    const std::int64_t vertex_at = a.columns.vertex_offsets[c], face_at = a.columns.face_offsets[c];
    const u32* corners = a.words + r.word_at;
    const u32* ids = corners + 3 * std::size_t{r.faces};
    const Point* xyz = a.coordinates + r.point_at;
    for (u32 v = lane; v < r.vertices; v += 32)
      a.columns.vertices[vertex_at + v] = static_cast<std::int32_t>(ids[v]);
    for (u32 f = lane; f < r.faces; f += 32) {
      const u32 w[3] = {corners[3 * f], corners[3 * f + 1], corners[3 * f + 2]};
      std::int32_t* face = a.columns.faces + 3 * (face_at + f);
      for (int j = 0; j < 3; ++j)
        face[j] = static_cast<std::int32_t>(ids[w[j]]);
      detail::facet_plane_in_range(to_vec3d(xyz[w[0]]), to_vec3d(xyz[w[1]]), to_vec3d(xyz[w[2]]),
                                   a.columns.planes + 4 * (face_at + f));
    }
    // As convex_hull() measures a mesh (describe.cpp, measure_solid; plane_impl.hpp, measure_mesh()):
    // the faces' terms from the first face's first corner, added in the mesh's order one after another, and
    // the exact pass where the first is uncertain: the same bits.  Each lane loads (and computes the terms
    // of) its own faces, and every lane adds them all in order from the shuffles: lane 0 alone, face after
    // face, took about half again as long (docs/benchmarks.md, "The measurements behind the code's
    // constants").
    const auto corner = [&](u32 f, int k) { return to_vec3d(xyz[corners[3 * f + k]]); };
    const Vec3d apex = corner(0, 0);
    static_assert(detail::SolidMeasures::kErrorSums == 32, "a lane an error sum");
    detail::SolidMeasures measures;
    double error_sum = 0;  // this lane's faces' bounds (f mod 32 = lane), as measure_mesh()'s sums
    for (u32 base = 0; base < r.faces; base += 32) {
      const u32 f = base + lane;
      detail::SolidMeasures::FaceTerms mine{0, 0, 0};
      if (f < r.faces)
        mine = detail::SolidMeasures::face_terms(corner(f, 0), corner(f, 1), corner(f, 2), apex);
      error_sum = detail::add_rn(error_sum, mine.six_volume_error);
      for (u32 j = 0; j < 32 && base + j < r.faces; ++j)
        measures.add_terms(
            {__shfl_sync(0xffffffffu, mine.twice_area, j), __shfl_sync(0xffffffffu, mine.six_volume, j), 0});
    }
    for (u32 j = 0; j < 32; ++j)
      measures.six_volume_error =
          detail::add_rn(measures.six_volume_error, __shfl_sync(0xffffffffu, error_sum, j));
    if (measures.volume_uncertain()) {  // the same sums on every lane: the warp takes the pass together
      measures.exact_volume_pass();
      for (u32 base = 0; base < r.faces; base += 32) {
        const u32 f = base + lane;
        const double mine = f < r.faces ? detail::SolidMeasures::exact_six_volume(corner(f, 0), corner(f, 1),
                                                                                  corner(f, 2), apex)
                                        : 0.0;
        for (u32 j = 0; j < 32 && base + j < r.faces; ++j)
          measures.add_exact(__shfl_sync(0xffffffffu, mine, j));
      }
    }
    if (lane == 0) {
      a.columns.volumes[c] = measures.volume();
      a.columns.areas[c] = measures.area();
      a.columns.dimensions[c] = 3;
    }
  }
}

}  // namespace

template <class Point>
void describe_batch_cuda(const BatchRun<Point>& run, const BatchColumns& columns) {
  for (const auto& output : run.outputs) {
    DescribeArgs<Point> a{};
    a.words = output->words.get();
    a.coordinates = output->coordinates.get();
    a.results = reinterpret_cast<const BatchResult*>(output->results.get());
    a.clouds = output->clouds.get();
    a.listed = output->listed;
    a.columns = columns;
    const u32 blocks = (output->listed + kDescribeThreads / 32 - 1) / (kDescribeThreads / 32);
    describe_kernel<Point><<<blocks, kDescribeThreads>>>(a);
    check(cudaGetLastError(), "launching the describe");
  }
  check(cudaDeviceSynchronize(), "describing the hulls (kernel fault)");
}

template void describe_batch_cuda(const BatchRun<Point3>&, const BatchColumns&);
template void describe_batch_cuda(const BatchRun<Point3d>&, const BatchColumns&);

}  // namespace cudahull
