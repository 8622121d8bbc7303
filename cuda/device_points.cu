#include "cudahull/cuda/device_points.hpp"

#include <cuda_runtime.h>

#include <algorithm>
#include <string>
#include <type_traits>

#include "cuda_errors.hpp"
#include "cudahull/cuda/device_memory.hpp"
#include "cudahull/cuda/host_transfer.hpp"
#include "cudahull/errors.hpp"
#include "cudahull/predicates.hpp"

namespace cudahull {

namespace {

constexpr const char* kWho = "device points";
constexpr unsigned kThreads = 256;

constexpr CudaCheck check{kWho};

// in_fast_exact_range() (predicates.hpp), the engines' range: a double outside it is not refused but sent
// to the host's wide-range path (convex_hull_device() reads its first such point and decides).
template <class Point, class Scalar>
__device__ bool acceptable(Scalar c, decltype(Point::x)& out) {
  const double v = static_cast<double>(c);
  if (!isfinite(v)) return false;
  if constexpr (std::is_same_v<Point, Point3d>) {
    out = v;
    return in_fast_exact_range(v);
  } else {
    // Rounded to nearest once (a float is unchanged), as static_cast<float> on the host.
    out = static_cast<float>(v);
    return isfinite(out);
  }
}

// Point i of `xyz` in Point's precision (into p), and whether the hull in Point can take it.
template <class Point, class Scalar>
__device__ bool acceptable_point(const Scalar* xyz, std::size_t i, Point& p) {
  return acceptable<Point>(xyz[3 * i], p.x) & acceptable<Point>(xyz[3 * i + 1], p.y) &
         acceptable<Point>(xyz[3 * i + 2], p.z);
}

// One pass: every point tested (the lowest failing index wins through atomicMin, so the error names the
// same point as the host path's scan) and, when `out` is given, written in Point's precision.
template <class Point, class Scalar>
__global__ void check_points_kernel(const Scalar* xyz, std::size_t count, Point* out,
                                    unsigned long long* first_bad) {
  const std::size_t stride = static_cast<std::size_t>(gridDim.x) * blockDim.x;
  for (std::size_t i = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x; i < count;
       i += stride) {
    Point p;
    const bool good = acceptable_point(xyz, i, p);
    if (!good) atomicMin(first_bad, static_cast<unsigned long long>(i));
    if (out) out[i] = p;
  }
}

// Each point that `acceptable` refuses marks its cloud: kCloudWide when every coordinate is finite and
// Point keeps Scalar's precision (a double outside the fast exact range), else kCloudBad.
template <class Point, class Scalar>
__global__ void check_clouds_kernel(const Scalar* xyz, std::size_t count, const unsigned long long* offsets,
                                    std::size_t clouds, unsigned* marks) {
  const std::size_t stride = static_cast<std::size_t>(gridDim.x) * blockDim.x;
  for (std::size_t i = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x; i < count;
       i += stride) {
    Point p;
    if (acceptable_point(xyz, i, p)) continue;
    const bool finite = isfinite(static_cast<double>(xyz[3 * i])) &&
                        isfinite(static_cast<double>(xyz[3 * i + 1])) &&
                        isfinite(static_cast<double>(xyz[3 * i + 2]));
    const bool wide = finite && std::is_same_v<decltype(Point::x), Scalar>;
    // The cloud that holds i: the last whose start is at or before it (empty clouds hold none).
    std::size_t lo = 0, hi = clouds;  // offsets[lo] <= i < offsets[hi]
    while (hi - lo > 1) {
      const std::size_t mid = lo + (hi - lo) / 2;
      if (offsets[mid] <= i)
        lo = mid;
      else
        hi = mid;
    }
    atomicOr(&marks[lo], wide ? unsigned{kCloudWide} : unsigned{kCloudBad});
  }
}

unsigned grid_for(std::size_t count) {
  // Enough blocks to fill the device several times over; more only adds blocks with nothing to do.
  return grid_stride_blocks(count, kThreads, 16);
}

}  // namespace

unsigned grid_stride_blocks(std::size_t count, unsigned threads, unsigned per_sm) {
  int device = 0, sms = 1;
  check(cudaGetDevice(&device), "reading the current device");
  check(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, device), "reading the SM count");
  const std::size_t needed = (count + threads - 1) / threads;
  return static_cast<unsigned>(
      std::max<std::size_t>(1, std::min<std::size_t>(needed, std::size_t{per_sm} * sms)));
}

bool cuda_device_present(std::string* why_not) {
  int count = 0;
  const cudaError_t e = cudaGetDeviceCount(&count);
  if (e != cudaSuccess) {
    cudaGetLastError();
    if (why_not) *why_not = cudaGetErrorString(e);
    return false;
  }
  if (count == 0 && why_not) *why_not = "no CUDA device found";
  return count > 0;
}

void require_current_device_memory(const void* xyz) {
  int current = 0;
  check(cudaGetDevice(&current), "reading the current device");
  cudaPointerAttributes attributes{};
  const cudaError_t e = cudaPointerGetAttributes(&attributes, xyz);
  if (e != cudaSuccess) {
    cudaGetLastError();
    throw DeviceError(std::string(kWho) + ": the array is not in CUDA device memory (" + cuda_error_text(e) +
                      ")");
  }
  if (attributes.type != cudaMemoryTypeDevice && attributes.type != cudaMemoryTypeManaged)
    throw DeviceError(std::string(kWho) + ": the array is not in CUDA device memory");
  if (attributes.device != current) {
    throw DeviceError(std::string(kWho) + ": the array is on CUDA device " +
                      std::to_string(attributes.device) + ", but the current device is " +
                      std::to_string(current) + ": make its device current (cupy.cuda.Device(" +
                      std::to_string(attributes.device) + ").use(), torch.cuda.set_device(" +
                      std::to_string(attributes.device) + "))");
  }
}

std::shared_ptr<void> upload_to_device(const void* host, std::size_t bytes) {
  std::shared_ptr<unsigned char> copy = shared_device_array<unsigned char>(bytes, kWho, "the points");
  copy_host_to_device(copy.get(), host, bytes, kWho, "uploading the points");
  return copy;
}

template <class Point, class Scalar>
CheckedDevicePoints<Point> check_device_points(const Scalar* xyz, std::size_t count) {
  CheckedDevicePoints<Point> result;
  result.count = count;
  result.first_bad = count;
  if (count == 0) return result;
  // CuPy and PyTorch may have written the array on a stream of their own, unordered with ours.
  check(cudaDeviceSynchronize(), "waiting for the array's producer");

  Point* out = nullptr;
  if constexpr (!std::is_same_v<decltype(Point::x), Scalar>) {
    const std::shared_ptr<Point> converted =
        shared_device_array<Point>(count, kWho, "the points in the hull's precision");
    out = converted.get();
    result.converted = converted;
    result.points = out;
  } else {
    result.points = reinterpret_cast<const Point*>(xyz);
  }

  const DeviceArray<unsigned long long> first_bad(1, kWho, "the check's result");
  check(cudaMemset(first_bad.get(), 0xff, sizeof(unsigned long long)), "clearing the check's result");
  check_points_kernel<Point, Scalar><<<grid_for(count), kThreads>>>(xyz, count, out, first_bad.get());
  check(cudaGetLastError(), "launching the check");
  unsigned long long bad = 0;
  check(cudaMemcpy(&bad, first_bad.get(), sizeof bad, cudaMemcpyDeviceToHost), "reading the check's result");
  result.host_syncs = 1;
  result.bytes_from_device = sizeof bad;
  result.first_bad = bad == ~0ull ? count : static_cast<std::size_t>(bad);
  return result;
}

template <class Point, class Scalar>
std::vector<std::uint8_t> check_device_clouds(const Scalar* xyz, std::size_t count,
                                              const std::size_t* offsets, std::size_t clouds) {
  std::vector<std::uint8_t> result(clouds, kCloudGood);
  if (count == 0 || clouds == 0) return result;
  static_assert(sizeof(std::size_t) == sizeof(unsigned long long));
  const DeviceArray<unsigned long long> bounds(clouds + 1, kWho, "the clouds' offsets");
  const DeviceArray<unsigned> marks(clouds, kWho, "the clouds' marks");
  check(cudaMemcpy(bounds.get(), offsets, (clouds + 1) * sizeof(unsigned long long), cudaMemcpyHostToDevice),
        "uploading the clouds' offsets");
  check(cudaMemset(marks.get(), 0, clouds * sizeof(unsigned)), "clearing the clouds' marks");
  check_clouds_kernel<Point, Scalar>
      <<<grid_for(count), kThreads>>>(xyz, count, bounds.get(), clouds, marks.get());
  check(cudaGetLastError(), "launching the clouds' check");
  std::vector<unsigned> host(clouds);
  check(cudaMemcpy(host.data(), marks.get(), clouds * sizeof(unsigned), cudaMemcpyDeviceToHost),
        "reading the clouds' marks");
  for (std::size_t c = 0; c < clouds; ++c)
    result[c] = host[c] & kCloudBad ? kCloudBad : static_cast<std::uint8_t>(host[c]);
  return result;
}

template <class Scalar>
std::array<double, 3> read_device_point(const Scalar* xyz, std::size_t index) {
  Scalar c[3];
  check(cudaMemcpy(c, xyz + 3 * index, sizeof c, cudaMemcpyDeviceToHost), "reading a point back");
  return {static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])};
}

template CheckedDevicePoints<Point3> check_device_points<Point3>(const float*, std::size_t);
template CheckedDevicePoints<Point3> check_device_points<Point3>(const double*, std::size_t);
template CheckedDevicePoints<Point3d> check_device_points<Point3d>(const float*, std::size_t);
template CheckedDevicePoints<Point3d> check_device_points<Point3d>(const double*, std::size_t);
template <class Scalar>
std::vector<Scalar> download_values(const Scalar* values, std::size_t count) {
  std::vector<Scalar> host(count);
  check(cudaDeviceSynchronize(), "waiting for the points' producer");
  check(cudaMemcpy(host.data(), values, count * sizeof(Scalar), cudaMemcpyDeviceToHost),
        "reading the points");
  return host;
}

template std::vector<std::uint8_t> check_device_clouds<Point3>(const float*, std::size_t, const std::size_t*,
                                                               std::size_t);
template std::vector<std::uint8_t> check_device_clouds<Point3>(const double*, std::size_t, const std::size_t*,
                                                               std::size_t);
template std::vector<std::uint8_t> check_device_clouds<Point3d>(const float*, std::size_t, const std::size_t*,
                                                                std::size_t);
template std::vector<std::uint8_t> check_device_clouds<Point3d>(const double*, std::size_t,
                                                                const std::size_t*, std::size_t);
template std::vector<float> download_values(const float*, std::size_t);
template std::vector<double> download_values(const double*, std::size_t);
template std::array<double, 3> read_device_point(const float*, std::size_t);
template std::array<double, 3> read_device_point(const double*, std::size_t);

}  // namespace cudahull
