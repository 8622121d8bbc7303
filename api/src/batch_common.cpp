// The offsets' check, a cloud's error, the backends' names and the batch's plan (batch_common.hpp).
#include "batch_common.hpp"

#include <charconv>
#include <stdexcept>
#include <string_view>

namespace cudahull::batch {

void check_offsets(std::size_t count, const std::size_t* offsets, std::size_t clouds) {
  if (offsets == nullptr)
    throw std::invalid_argument("convex_hull_batch: no offsets (B + 1 of them are needed)");
  if (offsets[0] != 0)
    throw std::invalid_argument("convex_hull_batch: offsets[0] is " + std::to_string(offsets[0]) +
                                ", not 0 (offsets are the B + 1 cloud boundaries in the packed points)");
  for (std::size_t c = 0; c < clouds; ++c) {
    if (offsets[c + 1] < offsets[c])
      throw std::invalid_argument("convex_hull_batch: offsets decrease at cloud " + std::to_string(c) + " (" +
                                  std::to_string(offsets[c]) + " then " + std::to_string(offsets[c + 1]) +
                                  ")");
  }
  if (offsets[clouds] != count)
    throw std::invalid_argument("convex_hull_batch: the last offset is " + std::to_string(offsets[clouds]) +
                                ", not the point count " + std::to_string(count));
}

InputError in_cloud(const InputError& error, std::size_t cloud, std::size_t first_row) {
  std::string message = "cloud " + std::to_string(cloud) + ": " + error.what();
  const std::string_view what = error.what();
  constexpr std::string_view kPoint = "point ";
  if (what.substr(0, kPoint.size()) == kPoint) {
    std::size_t point = 0;
    const char* digits = what.data() + kPoint.size();
    const auto [end, status] = std::from_chars(digits, what.data() + what.size(), point);
    if (status == std::errc() && end != digits && *end == ':')
      message += " (row " + std::to_string(first_row + point) + " of the packed points)";
  }
  return InputError(message);
}

void add_backend(ConvexHullBatchReport& report, const std::string& name) {
  if (report.backend.empty()) {
    report.backend = name;
  } else if (!name.empty() && ("+" + report.backend + "+").find("+" + name + "+") == std::string::npos) {
    report.backend += "+" + name;
  }
}

HullPlan batch_plan(std::size_t count, Precision own, bool on_device, const ConvexHullOptions& options) {
  HullInput input;
  input.precision = own;
  input.count = count;
  input.on_device = on_device;
  return plan_hull(options, input, cuda_presence);
}

}  // namespace cudahull::batch
