#pragma once
// HugePageAllocator: storage for a large array the tick reads at random places (a 4096 x 4096
// stiffness map is 64 MiB), backed by 2 MiB pages where the kernel offers them.
//
// Why: a pen jumping across such a map makes every scene sample a TLB miss as well as a cache
// miss. With 4 KiB pages the map is 16,384 pages, far more than the TLB holds, and each miss
// is a page-table walk (under a hypervisor's nested paging, up to 24 memory reads); with 2 MiB
// pages it is 32 pages, which the TLB holds whole. Linux gives transparent huge pages to a
// 2 MiB-aligned range that asks for them with madvise(MADV_HUGEPAGE) before it is first touched
// (the default policy of Debian's kernel is "madvise"; with "never" the advice is ignored and the
// array keeps 4 KiB pages, which is only slower). Neither the standard library nor the libraries
// palprig uses offer such an allocator, hence these few lines by hand.
//
// Arrays under 2 MiB gain nothing (they fit in a few hundred 4 KiB pages) and come from
// std::allocator as before; deallocate tells the two apart by the size it is given back, which
// the standard guarantees is the size that was allocated.
#include <sys/mman.h>

#include <cstddef>
#include <cstdlib>
#include <limits>
#include <memory>
#include <new>

namespace palprig {

inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

template <class T>
struct HugePageAllocator {
  using value_type = T;

  HugePageAllocator() noexcept = default;
  template <class U>
  explicit HugePageAllocator(const HugePageAllocator<U>& /*other*/) noexcept {}

  static bool huge(std::size_t n) noexcept { return n * sizeof(T) >= kHugePageBytes; }

  T* allocate(std::size_t n) {
    if (n > (std::numeric_limits<std::size_t>::max() - kHugePageBytes) / sizeof(T)) throw std::bad_array_new_length();
    if (!huge(n)) return std::allocator<T>{}.allocate(n);
    const std::size_t bytes = (n * sizeof(T) + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    void* p = std::aligned_alloc(kHugePageBytes, bytes);
    if (p == nullptr) throw std::bad_alloc();
    // Advice only: where transparent huge pages are off it fails or is ignored, and the array
    // simply keeps 4 KiB pages.
    (void)madvise(p, bytes, MADV_HUGEPAGE);
    return static_cast<T*>(p);
  }

  void deallocate(T* p, std::size_t n) noexcept {
    if (huge(n))
      std::free(p);
    else
      std::allocator<T>{}.deallocate(p, n);
  }

  template <class U>
  bool operator==(const HugePageAllocator<U>& /*other*/) const noexcept {
    return true;  // stateless: any instance frees what another allocated
  }
};

}  // namespace palprig
