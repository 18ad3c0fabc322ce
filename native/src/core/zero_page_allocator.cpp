// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/zero_page_allocator.h"

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>

namespace hyvox::detail {
namespace {
// Below this, calloc is as good (it reuses heap memory and zeroes little).
constexpr std::size_t kMapThreshold = std::size_t(1) << 20;
}  // namespace

void* allocateZeroPages(std::size_t bytes) {
    if (bytes == 0) bytes = 1;
    if (bytes < kMapThreshold) {
        void* p = std::calloc(1, bytes);
        if (!p) throw std::bad_alloc();
        return p;
    }
    void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
    madvise(p, bytes, MADV_HUGEPAGE);  // a hint: 512× fewer page faults where THP is allowed
#endif
    return p;
}

void freeZeroPages(void* p, std::size_t bytes) {
    if (!p) return;
    if (bytes == 0) bytes = 1;
    if (bytes < kMapThreshold)
        std::free(p);
    else
        munmap(p, bytes);
}

}  // namespace hyvox::detail

namespace hyvox {

void adviseHugePages(void* p, std::size_t bytes) noexcept {
#ifdef MADV_HUGEPAGE
    constexpr std::uintptr_t kHuge = std::uintptr_t(1) << 21;
    const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(p) + kHuge - 1) & ~(kHuge - 1);
    const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~(kHuge - 1);
    if (p && end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
    (void)p;
    (void)bytes;
#endif
}

}  // namespace hyvox
