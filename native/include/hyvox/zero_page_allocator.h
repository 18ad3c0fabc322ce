// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// An allocator for large arrays that start as all zeros (the bit grid). Zeroing 16 MiB with
// memset costs ~30 ms of page faults on one thread before any work starts; fresh anonymous
// pages are zero already, so this allocator hands those out untouched (asking for huge
// pages) and lets the voxelizer's threads fault in only the pages the surface touches.
// Value-initialising construct() is a no-op because the memory is already zero.
#include <cstddef>
#include <new>
#include <utility>

namespace hyvox {

namespace detail {
void* allocateZeroPages(std::size_t bytes);
void freeZeroPages(void* p, std::size_t bytes);
}  // namespace detail

// Asks for huge pages under [p, p + bytes) (the 2 MiB-aligned part of it) before its pages are
// first written: each 4 KiB first touch is a page fault, and arrays of millions of triangles
// spend more time in those faults than in filling them. A hint: without THP it does nothing.
void adviseHugePages(void* p, std::size_t bytes) noexcept;

template <typename T>
struct ZeroPageAllocator {
    using value_type = T;
    ZeroPageAllocator() = default;
    template <typename U>
    ZeroPageAllocator(const ZeroPageAllocator<U>&) noexcept {}

    T* allocate(std::size_t n) { return static_cast<T*>(detail::allocateZeroPages(n * sizeof(T))); }
    void deallocate(T* p, std::size_t n) noexcept { detail::freeZeroPages(p, n * sizeof(T)); }

    template <typename U>
    void construct(U*) noexcept {}  // value-initialisation: the pages are zero already
    template <typename U, typename... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }

    template <typename U>
    bool operator==(const ZeroPageAllocator<U>&) const noexcept { return true; }
    template <typename U>
    bool operator!=(const ZeroPageAllocator<U>&) const noexcept { return false; }
};

}  // namespace hyvox
