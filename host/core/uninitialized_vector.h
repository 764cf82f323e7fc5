// A std::vector whose resize leaves new elements of a trivial type as the memory holds
// them, for an array about to be written whole: std::vector<T>::resize value-initialises,
// which for the grid's PE triangles was a 50 MB memset on one core (~5 ms of the scattered
// copies' build, 2 cores, AMD EPYC, KVM, 2026-12-03) before every element was overwritten.
// The allocator's one-argument construct does default-initialisation instead (nothing, for
// a trivial type); every other construct is std::allocator's.
#pragma once
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace gridrt {

template <typename T>
class DefaultInitAllocator : public std::allocator<T> {
 public:
  template <typename U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() noexcept = default;
  template <typename U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}

  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <typename T>
using UninitializedVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace gridrt
