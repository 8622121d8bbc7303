// Where the readers' bytes come from: a buffered line and byte source over an istream, the progress
// callback, opening a file, and the end of a point list.  Internal to io/.
#pragma once

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "cudahull/point_io.hpp"
#include "read_failures.hpp"

namespace cudahull::reading {

inline constexpr std::size_t kMaxLineBytes = std::size_t{16} << 20;      // a longer "line" is binary garbage
inline constexpr std::uint64_t kProgressEvery = std::uint64_t{1} << 16;  // points between callbacks

// Calls the progress callback every kProgressEvery points, never per point.
class Progress {
 public:
  explicit Progress(const ProgressFn& fn) : fn_(fn) {}
  bool enabled() const { return static_cast<bool>(fn_); }
  bool due(std::uint64_t points) const { return fn_ && points % kProgressEvery == 0; }
  void report(double fraction) const {
    if (fn_) fn_(std::clamp(fraction, 0.0, 1.0));
  }

 private:
  const ProgressFn& fn_;
};

// A buffered reader over an istream that hands out lines (as views into its buffer) and raw bytes, so one
// PLY file can be read as header lines and then binary data.
class Source {
 public:
  Source(std::istream& in, const std::string& name) : in_(in), name_(name), buffer_(std::size_t{1} << 20) {
    // The size left in the stream, where it can be seeked, bounds the counts a header may claim.
    const std::istream::pos_type start = in_.tellg();
    if (start != std::istream::pos_type(-1) && in_.seekg(0, std::ios::end)) {
      const std::istream::pos_type end = in_.tellg();
      if (end != std::istream::pos_type(-1) && end >= start) size_ = static_cast<std::uint64_t>(end - start);
    }
    in_.clear();
    in_.seekg(start);
    in_.clear();
  }

  // Bytes the stream held when the reading began, if it can tell.
  std::optional<std::uint64_t> size() const { return size_; }
  std::uint64_t consumed() const { return consumed_; }
  std::optional<std::uint64_t> remaining() const {
    if (!size_) return std::nullopt;
    return *size_ >= consumed_ ? *size_ - consumed_ : 0;
  }
  std::uint64_t line_number() const { return line_; }
  double fraction() const { return size_ && *size_ > 0 ? double(consumed_) / double(*size_) : 0.0; }

  // The next line without its end-of-line characters; false at the end of the data.
  bool next_line(std::string_view& line) {
    while (true) {
      const char* begin = buffer_.data() + pos_;
      const void* nl = std::memchr(begin, '\n', end_ - pos_);
      if (nl != nullptr) {
        const std::size_t len = static_cast<const char*>(nl) - begin;
        line = trim_cr(std::string_view(begin, len));
        pos_ += len + 1;
        consumed_ += len + 1;
        ++line_;
        return true;
      }
      if (eof_) {
        if (pos_ == end_) return false;
        line = trim_cr(std::string_view(begin, end_ - pos_));
        consumed_ += end_ - pos_;
        pos_ = end_;
        ++line_;
        return true;
      }
      if (end_ - pos_ >= kMaxLineBytes) fail_line(name_, line_ + 1, "line longer than 16 MiB (binary data?)");
      compact_and_fill();
    }
  }

  // Reads up to n bytes; returns how many were read (fewer only at the end of the data).
  std::size_t read_bytes(char* dst, std::size_t n) {
    std::size_t done = std::min(n, end_ - pos_);
    std::memcpy(dst, buffer_.data() + pos_, done);
    pos_ += done;
    while (done < n && !eof_) {
      const std::size_t want = n - done;
      if (want >= buffer_.size() / 2) {
        // Big requests bypass the buffer: one large read per chunk is what keeps this at disk speed.
        done += raw_read(dst + done, want);
      } else {
        compact_and_fill();
        const std::size_t take = std::min(want, end_ - pos_);
        std::memcpy(dst + done, buffer_.data() + pos_, take);
        pos_ += take;
        done += take;
      }
    }
    consumed_ += done;
    return done;
  }

  // Skips n bytes; returns how many were skipped.
  std::uint64_t skip_bytes(std::uint64_t n) {
    std::uint64_t done = 0;
    while (true) {
      const std::size_t take = static_cast<std::size_t>(std::min<std::uint64_t>(n - done, end_ - pos_));
      pos_ += take;
      done += take;
      if (done == n || eof_) break;
      pos_ = 0;
      end_ = raw_read(buffer_.data(), buffer_.size());
    }
    consumed_ += done;
    return done;
  }

 private:
  static std::string_view trim_cr(std::string_view s) {
    return !s.empty() && s.back() == '\r' ? s.substr(0, s.size() - 1) : s;
  }

  std::size_t raw_read(char* dst, std::size_t n) {
    std::size_t done = 0;
    while (done < n && !eof_) {
      in_.read(dst + done, static_cast<std::streamsize>(n - done));
      const std::size_t got = static_cast<std::size_t>(in_.gcount());
      if (in_.bad()) fail(name_, "read error");
      done += got;
      if (got == 0 || in_.eof()) eof_ = true;
    }
    return done;
  }

  void compact_and_fill() {
    if (pos_ > 0) {
      std::memmove(buffer_.data(), buffer_.data() + pos_, end_ - pos_);
      end_ -= pos_;
      pos_ = 0;
    }
    if (end_ == buffer_.size()) buffer_.resize(buffer_.size() * 2);
    end_ += raw_read(buffer_.data() + end_, buffer_.size() - end_);
  }

  std::istream& in_;
  const std::string& name_;
  std::vector<char> buffer_;
  std::size_t pos_ = 0, end_ = 0;
  bool eof_ = false;
  std::uint64_t consumed_ = 0;
  std::uint64_t line_ = 0;
  std::optional<std::uint64_t> size_;
};

template <typename P>
void finish(std::vector<P>& points, const Source& src, const std::string& name, const char* what,
            const Progress& progress) {
  if (points.empty()) fail(name, src.consumed() == 0 ? "empty file" : what);
  progress.report(1.0);
}

// Opens a point file for reading, or throws naming it.
inline void open_file(const std::string& path, std::ifstream& in) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(path, "is a directory");
  in.open(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot open: ") + std::strerror(errno));
}

inline std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

}  // namespace cudahull::reading
