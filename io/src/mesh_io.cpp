// Hull writers (OBJ, OFF, ascii PLY), the vertex list writer and the atomic file writer.  The writers are
// templates on the point type, instantiated for Point3 (float, %.9g) and Point3d (double, %.17g).
#include "cudahull/mesh_io.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <mutex>
#include <numeric>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "cudahull/errors.hpp"

namespace cudahull {
namespace {

// ------------------------------------------------------------------ temporary files and interrupts
//
// A SIGINT, SIGTERM or SIGHUP (the terminal closed) while a temporary file exists unlinks it and then dies
// by the signal as before.  A signal the caller set to be ignored stays ignored (nothing is interrupted, so
// nothing is left behind).  The handler may only touch async-signal-safe state: fixed buffers and lock-free
// atomics.  A few slots let several threads write at once.

constexpr int kTempSlots = 8;
constexpr std::size_t kTempPathMax = 4096;
char g_temp_paths[kTempSlots][kTempPathMax];
std::atomic<bool> g_temp_active[kTempSlots];
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs lock-free atomics");

std::mutex g_temp_mutex;  // guards slot claims and handler (un)installation, never used in the handler
bool g_slot_claimed[kTempSlots];
int g_active_writers = 0;
constexpr int kHandledSignals[] = {SIGINT, SIGTERM, SIGHUP};
constexpr int kHandledCount = static_cast<int>(std::size(kHandledSignals));
struct sigaction g_old_actions[kHandledCount];
bool g_installed[kHandledCount];

extern "C" void unlink_temps_and_reraise(int sig) {
  for (int i = 0; i < kTempSlots; ++i) {
    if (g_temp_active[i].load()) ::unlink(g_temp_paths[i]);
  }
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  ::sigaction(sig, &dfl, nullptr);
  // The signal is blocked inside its handler: it is delivered, with the default action, on return.
  ::raise(sig);
}

// Registers a temporary file for removal on SIGINT/SIGTERM for as long as it lives.
class TempFileGuard {
 public:
  explicit TempFileGuard(const std::string& path) {
    std::lock_guard lock(g_temp_mutex);
    if (path.size() >= kTempPathMax) return;  // unprotected, but still removed on errors
    for (int i = 0; i < kTempSlots; ++i) {
      if (g_slot_claimed[i]) continue;
      g_slot_claimed[i] = true;
      slot_ = i;
      std::memcpy(g_temp_paths[i], path.c_str(), path.size() + 1);
      g_temp_active[i].store(true);
      break;
    }
    if (slot_ < 0) return;
    if (g_active_writers++ == 0) {
      struct sigaction sa {};
      sa.sa_handler = unlink_temps_and_reraise;
      sigemptyset(&sa.sa_mask);
      for (int k = 0; k < kHandledCount; ++k) {
        g_installed[k] = false;
        if (::sigaction(kHandledSignals[k], nullptr, &g_old_actions[k]) != 0) continue;
        if (g_old_actions[k].sa_handler == SIG_IGN) continue;  // ignored by the caller: leave it so
        g_installed[k] = ::sigaction(kHandledSignals[k], &sa, nullptr) == 0;
      }
    }
  }
  ~TempFileGuard() {
    if (slot_ < 0) return;
    std::lock_guard lock(g_temp_mutex);
    g_temp_active[slot_].store(false);
    g_slot_claimed[slot_] = false;
    if (--g_active_writers == 0) {
      for (int k = 0; k < kHandledCount; ++k) {
        if (g_installed[k]) ::sigaction(kHandledSignals[k], &g_old_actions[k], nullptr);
      }
    }
  }
  TempFileGuard(const TempFileGuard&) = delete;
  TempFileGuard& operator=(const TempFileGuard&) = delete;

 private:
  int slot_ = -1;
};

std::string temp_path_for(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path target(path);
  std::string name = ".";
  name += target.filename().string();
  name += ".tmp.";
  name += std::to_string(::getpid());
  name += '.';
  name += std::to_string(counter.fetch_add(1));
  return (target.parent_path() / name).string();
}

[[noreturn]] void fail_output(const std::string& path, const std::string& what) {
  throw OutputError("cannot write " + path + ": " + what);
}

// Flushes the data to disk so that the rename never publishes a file whose contents a crash could lose.
void sync_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// ------------------------------------------------------------------ formatting

// Buffers formatted text and hands it to the stream in large pieces.
class TextOut {
 public:
  explicit TextOut(std::ostream& out) : out_(out) { buf_.reserve(kFlushAt + 256); }
  ~TextOut() = default;
  TextOut& str(std::string_view s) {
    buf_ += s;
    maybe_flush();
    return *this;
  }
  TextOut& uint(std::uint64_t v) {
    char tmp[24];
    const int n = std::snprintf(tmp, sizeof tmp, "%llu", static_cast<unsigned long long>(v));
    buf_.append(tmp, static_cast<std::size_t>(n));
    return *this;
  }
  // %.9g: nine significant digits read back as the same float.
  TextOut& coord(float v) {
    char tmp[32];
    const int n = std::snprintf(tmp, sizeof tmp, "%.9g", static_cast<double>(v));
    buf_.append(tmp, static_cast<std::size_t>(n));
    return *this;
  }
  // %.17g: seventeen significant digits read back as the same double.
  TextOut& coord(double v) {
    char tmp[40];
    const int n = std::snprintf(tmp, sizeof tmp, "%.17g", v);
    buf_.append(tmp, static_cast<std::size_t>(n));
    return *this;
  }
  template <class Point>
  TextOut& point(const Point& p) {
    return coord(p.x).str(" ").coord(p.y).str(" ").coord(p.z);
  }
  void flush() {
    out_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
    buf_.clear();
  }

 private:
  static constexpr std::size_t kFlushAt = std::size_t{1} << 20;
  void maybe_flush() {
    if (buf_.size() >= kFlushAt) flush();
  }
  std::ostream& out_;
  std::string buf_;
};

enum class MeshFormat { kObj, kOff, kPly };

// The format `path` names, or false with *why set.
bool find_mesh_format(const std::string& path, MeshFormat* format, std::string* why) {
  // "-" has no extension; OBJ is the format most tools read from a pipe.
  if (path == "-") {
    *format = MeshFormat::kObj;
    return true;
  }
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".obj")
    *format = MeshFormat::kObj;
  else if (ext == ".off")
    *format = MeshFormat::kOff;
  else if (ext == ".ply")
    *format = MeshFormat::kPly;
  else {
    *why = "unknown mesh extension '" + ext + "' (expected .obj, .off or .ply)";
    return false;
  }
  return true;
}

MeshFormat mesh_format(const std::string& path) {
  MeshFormat format;
  std::string why;
  if (!find_mesh_format(path, &format, &why)) throw OutputError("cannot write " + path + ": " + why);
  return format;
}

// The faces to write: the triangles, the one polygon of a planar hull, or none for a segment or a point.
template <class Point>
class Faces {
 public:
  Faces(const BasicHullMesh<Point>& hull, const std::string& path) : hull_(hull) {
    if (hull.dimension == 3) {
      count_ = hull.triangles.size();
    } else if (hull.dimension == 2 && hull.polygon.size() >= 3) {
      count_ = 1;
    }
    for (std::size_t i = 0; i < count_; ++i) {
      for (std::uint32_t v : (*this)[i]) {
        if (v >= hull.vertices.size()) {
          fail_output(path, "invalid hull: a face refers to vertex " + std::to_string(v) + " of " +
                                std::to_string(hull.vertices.size()));
        }
      }
    }
  }
  std::size_t size() const { return count_; }
  std::span<const std::uint32_t> operator[](std::size_t i) const {
    if (hull_.dimension == 3) return {hull_.triangles[i].data(), 3};
    return hull_.polygon;
  }
  std::size_t longest() const { return count_ == 0 ? 0 : hull_.dimension == 3 ? 3 : hull_.polygon.size(); }

 private:
  const BasicHullMesh<Point>& hull_;
  std::size_t count_ = 0;
};

template <class Point>
void write_obj(std::ostream& os, const BasicHullMesh<Point>& hull, const Faces<Point>& faces) {
  TextOut out(os);
  out.str("# cudahull convex hull: ").uint(hull.vertices.size()).str(" vertices, ").uint(faces.size());
  out.str(" faces\n");
  for (const Point& p : hull.vertices)
    out.str("v ").point(p).str("\n");
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const auto f = faces[i];
    out.str("f");
    for (std::uint32_t v : f)
      out.str(" ").uint(std::uint64_t{v} + 1);  // OBJ counts from 1
    out.str("\n");
  }
  out.flush();
}

// The part OFF and ASCII PLY share: one vertex per line, then each face as "count i j k ...".
template <class Point>
void write_counted_body(TextOut& out, const BasicHullMesh<Point>& hull, const Faces<Point>& faces) {
  for (const Point& p : hull.vertices)
    out.point(p).str("\n");
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const auto f = faces[i];
    out.uint(f.size());
    for (std::uint32_t v : f)
      out.str(" ").uint(v);
    out.str("\n");
  }
  out.flush();
}

template <class Point>
void write_off(std::ostream& os, const BasicHullMesh<Point>& hull, const Faces<Point>& faces) {
  TextOut out(os);
  out.str("OFF\n").uint(hull.vertices.size()).str(" ").uint(faces.size()).str(" 0\n");
  write_counted_body(out, hull, faces);
}

template <class Point>
void write_ply(std::ostream& os, const BasicHullMesh<Point>& hull, const Faces<Point>& faces) {
  const std::size_t longest = faces.longest();
  TextOut out(os);
  out.str("ply\nformat ascii 1.0\ncomment cudahull convex hull\nelement vertex ").uint(hull.vertices.size());
  // The coordinates' own type: a reader that honours it keeps every digit written.
  out.str(std::is_same_v<Point, Point3d> ? "\nproperty double x\nproperty double y\nproperty double z"
                                         : "\nproperty float x\nproperty float y\nproperty float z");
  out.str("\nelement face ").uint(faces.size());
  // uchar counts are what most readers expect; a polygon of more than 255 corners needs a wider one.
  out.str(longest > 255 ? "\nproperty list uint int vertex_indices\n"
                        : "\nproperty list uchar int vertex_indices\n");
  out.str("end_header\n");
  write_counted_body(out, hull, faces);
}

}  // namespace

std::string mesh_path_problem(const std::string& path) {
  MeshFormat format;
  std::string why;
  return find_mesh_format(path, &format, &why) ? std::string() : why;
}

template <class Point>
void write_mesh(const std::string& path, const BasicHullMesh<Point>& hull) {
  const MeshFormat format = mesh_format(path);
  const Faces<Point> faces(hull, path);
  write_file_atomically(path, [&](std::ostream& os) {
    switch (format) {
      case MeshFormat::kObj:
        write_obj(os, hull, faces);
        break;
      case MeshFormat::kOff:
        write_off(os, hull, faces);
        break;
      case MeshFormat::kPly:
        write_ply(os, hull, faces);
        break;
    }
  });
}

template <class Point>
void write_vertices(const std::string& path, const BasicHullMesh<Point>& hull) {
  if (hull.vertex_ids.size() != hull.vertices.size()) {
    fail_output(path, "invalid hull: " + std::to_string(hull.vertex_ids.size()) + " vertex ids for " +
                          std::to_string(hull.vertices.size()) + " vertices");
  }
  std::vector<std::size_t> order(hull.vertices.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return hull.vertex_ids[a] < hull.vertex_ids[b]; });
  write_file_atomically(path, [&](std::ostream& os) {
    TextOut out(os);
    for (std::size_t i : order)
      out.uint(hull.vertex_ids[i]).str(" ").point(hull.vertices[i]).str("\n");
    out.flush();
  });
}

template void write_mesh(const std::string&, const HullMesh&);
template void write_mesh(const std::string&, const HullMeshd&);
template void write_vertices(const std::string&, const HullMesh&);
template void write_vertices(const std::string&, const HullMeshd&);

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write_body) {
  if (path == "-") {
    try {
      write_body(std::cout);
      std::cout.flush();
    } catch (const OutputError&) {
      throw;
    } catch (const std::exception& e) {
      fail_output("standard output", e.what());
    }
    if (!std::cout) fail_output("standard output", "write error");
    return;
  }

  const std::string temp = temp_path_for(path);
  TempFileGuard guard(temp);
  std::ofstream out(temp, std::ios::binary | std::ios::trunc);
  if (!out) fail_output(path, std::strerror(errno));
  try {
    write_body(out);
    out.flush();
    if (!out) fail_output(path, std::string("write error: ") + std::strerror(errno));
    out.close();
    if (out.fail()) fail_output(path, std::string("write error: ") + std::strerror(errno));
    sync_file(temp);
    if (std::rename(temp.c_str(), path.c_str()) != 0) {
      fail_output(path, std::string("rename failed: ") + std::strerror(errno));
    }
  } catch (const OutputError&) {
    out.close();
    std::remove(temp.c_str());
    throw;
  } catch (const std::exception& e) {
    out.close();
    std::remove(temp.c_str());
    fail_output(path, e.what());
  } catch (...) {
    out.close();
    std::remove(temp.c_str());
    fail_output(path, "unknown error");
  }
}

}  // namespace cudahull
