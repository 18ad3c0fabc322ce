// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/zero_page_allocator.h"

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>

namespace hyvox::detail {
namespace {
// Below this, calloc is as good (it reuses heap memory and zeroes little).
constexpr std::size_t kMapThreshold = std::size_t(1) << 20;
constexpr std::uintptr_t kHugePage = std::uintptr_t(1) << 21;

std::size_t roundUpToHugePages(std::size_t bytes) { return (bytes + kHugePage - 1) & ~std::size_t(kHugePage - 1); }

// An anonymous mapping of roundUpToHugePages(bytes) starting on a 2 MiB boundary. mmap only
// aligns to 4 KiB (this kernel aligns to 2 MiB only lengths that are multiples of it), and
// huge pages cover just the aligned middle of a mapping: up to 2 MiB at each end would be
// faulted in 4 KiB at a time (~500 faults per end). So map one huge page more and unmap the
// unaligned head and the tail beyond the rounded length.
void* mapHugeAligned(std::size_t bytes) {
    const std::size_t length = roundUpToHugePages(bytes);
    void* raw = mmap(nullptr, length + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) throw std::bad_alloc();
    const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(raw);
    const std::uintptr_t begin = (start + kHugePage - 1) & ~(kHugePage - 1);
    const std::uintptr_t end = start + length + kHugePage;
    if (begin > start) munmap(raw, begin - start);
    if (end > begin + length) munmap(reinterpret_cast<void*>(begin + length), end - (begin + length));
    return reinterpret_cast<void*>(begin);
}
}  // namespace

void* allocateZeroPages(std::size_t bytes) {
    if (bytes == 0) bytes = 1;
    if (bytes < kMapThreshold) {
        void* p = std::calloc(1, bytes);
        if (!p) throw std::bad_alloc();
        return p;
    }
    void* p = mapHugeAligned(bytes);
#ifdef MADV_HUGEPAGE
    madvise(p, roundUpToHugePages(bytes), MADV_HUGEPAGE);  // a hint: 512× fewer page faults where THP is allowed
#endif
    return p;
}

void freeZeroPages(void* p, std::size_t bytes) {
    if (!p) return;
    if (bytes == 0) bytes = 1;
    if (bytes < kMapThreshold)
        std::free(p);
    else
        munmap(p, roundUpToHugePages(bytes));
}

}  // namespace hyvox::detail

namespace hyvox {

std::size_t zeroPagesMapped(std::size_t bytes) noexcept {
    return bytes < detail::kMapThreshold ? bytes : detail::roundUpToHugePages(bytes);
}

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
