// ZeroedArray: a fixed-size array of zeros whose pages cost nothing until written.
#ifndef SPEEDUPS_ZEROED_ARRAY_H
#define SPEEDUPS_ZEROED_ARRAY_H

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>
#include <type_traits>

namespace povrayfc {

// std::vector<T>(n) writes every element: for a frame's worth of per-pixel memo that is
// every page touched, 200 MB at 3840x2160, also in a renderer of frame division that
// writes one 80x80 tile of it. calloc hands out large blocks as fresh mappings, zero by
// construction, so only the pages a writer touches are ever made (the same zeros).
template <typename T>
class ZeroedArray {
    static_assert(std::is_trivially_copyable<T>::value, "ZeroedArray holds plain values");

  public:
    // n zeros (none: released). Throws std::bad_alloc when memory runs out.
    void Reset(std::size_t n) {
        data_.reset();
        size_ = 0;
        if (n == 0) return;
        void *p = std::calloc(n, sizeof(T));
        if (!p) throw std::bad_alloc();
        data_.reset(static_cast<T *>(p));
        size_ = n;
    }
    void Release() { Reset(0); }

    bool empty() const { return size_ == 0; }
    std::size_t size() const { return size_; }
    T &operator[](std::size_t i) { return data_.get()[i]; }
    const T &operator[](std::size_t i) const { return data_.get()[i]; }

  private:
    struct Free {
        void operator()(T *p) const { std::free(p); }
    };
    std::unique_ptr<T, Free> data_;
    std::size_t size_ = 0;
};

}  // namespace povrayfc

#endif
