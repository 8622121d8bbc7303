// A fixed-size array of zeros that costs nothing until touched: calloc hands large blocks out as untouched
// zero pages, so a per-point table for 20M points does not cost a 20M-entry memset per run (the engine
// touches only the entries of the few thousand points that ever become vertices).
#pragma once

#include <cstdlib>
#include <memory>
#include <new>

namespace cudahull {

template <class T>
class ZeroedArray {
 public:
  ZeroedArray() = default;
  explicit ZeroedArray(std::size_t size)
      : data_(static_cast<T*>(std::calloc(size ? size : 1, sizeof(T)))), size_(size) {
    if (!data_) throw std::bad_alloc();
  }
  T& operator[](std::size_t i) { return data_.get()[i]; }
  const T& operator[](std::size_t i) const { return data_.get()[i]; }
  std::size_t size() const { return size_; }

 private:
  struct Free {
    void operator()(T* p) const { std::free(p); }
  };
  std::unique_ptr<T, Free> data_;
  std::size_t size_ = 0;
};

}  // namespace cudahull
