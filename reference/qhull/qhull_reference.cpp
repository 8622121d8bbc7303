// Qhull (libqhull_r, reentrant) run in-process.  See qhull_reference.hpp.
#include "qhull_reference.hpp"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <memory>
#include <stdexcept>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace cudahull {
namespace {

// Qhull writes its diagnostics to a FILE*; capture them so the caller gets the message in the exception and
// nothing reaches our stderr.
struct ErrFile {
  std::FILE* file = std::tmpfile();
  ErrFile() {
    if (file == nullptr) file = std::fopen("/dev/null", "w");
  }
  ~ErrFile() {
    if (file != nullptr) std::fclose(file);
  }
  ErrFile(const ErrFile&) = delete;
  ErrFile& operator=(const ErrFile&) = delete;

  // First non-empty line Qhull wrote (its error code and message), or "" if none could be read.
  std::string first_line() const {
    if (file == nullptr) return {};
    std::fflush(file);
    if (std::fseek(file, 0, SEEK_SET) != 0) return {};
    char buffer[1024];
    while (std::fgets(buffer, sizeof buffer, file) != nullptr) {
      std::string line(buffer);
      while (!line.empty() && (line.back() == '\n' || line.back() == '\r' || line.back() == ' ')) {
        line.pop_back();
      }
      if (!line.empty()) return line;
    }
    return {};
  }
};

// Frees Qhull's memory on every path, including exceptions.
struct QhullSession {
  std::unique_ptr<qhT> storage = std::make_unique<qhT>();
  qhT* qh = storage.get();
  explicit QhullSession(std::FILE* errfile) { qh_zero(qh, errfile); }
  ~QhullSession() {
    qh_freeqhull(qh, !qh_ALL);
    int curlong = 0, totlong = 0;
    qh_memfreeshort(qh, &curlong, &totlong);
  }
  QhullSession(const QhullSession&) = delete;
  QhullSession& operator=(const QhullSession&) = delete;
};

}  // namespace

template <class Point>
QhullResult run_qhull(const std::vector<Point>& points, const std::string& options) {
  if (points.empty()) throw std::runtime_error("qhull failed: no input points");
  if (points.size() > static_cast<std::size_t>(INT_MAX / 3)) {
    throw std::runtime_error("qhull: too many points (" + std::to_string(points.size()) + ")");
  }
  static_assert(sizeof(coordT) == sizeof(double), "Qhull built with realT double");
  std::vector<coordT> coords(points.size() * 3);  // exact for float and double coordinates
  for (std::size_t i = 0; i < points.size(); ++i) {
    coords[3 * i] = points[i].x;
    coords[3 * i + 1] = points[i].y;
    coords[3 * i + 2] = points[i].z;
  }
  std::string command = options.empty() ? std::string("qhull") : "qhull " + options;

  ErrFile err;
  QhullSession session(err.file);
  qhT* qh = session.qh;  // the FORALL macros name it `qh`
  QhullResult result;

  auto start = std::chrono::steady_clock::now();
  int exitcode = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False, command.data(),
                              nullptr, err.file);
  if (exitcode != 0) {
    std::string message = err.first_line();
    if (message.empty()) message = "no message";
    throw std::runtime_error("qhull failed (exit code " + std::to_string(exitcode) + "): " + message);
  }
  vertexT* vertex;
  result.vertex_ids.reserve(static_cast<std::size_t>(qh->num_vertices));
  FORALLvertices {
    result.vertex_ids.push_back(static_cast<PointIndex>(qh_pointid(qh, vertex->point)));
  }
  facetT* facet;
  FORALLfacets {
    if (!facet->visible) ++result.facets;
  }
  auto stop = std::chrono::steady_clock::now();
  result.milliseconds = std::chrono::duration<double, std::milli>(stop - start).count();

  std::sort(result.vertex_ids.begin(), result.vertex_ids.end());
  return result;
}

template QhullResult run_qhull(const std::vector<Point3>&, const std::string&);
template QhullResult run_qhull(const std::vector<Point3d>&, const std::string&);

}  // namespace cudahull
