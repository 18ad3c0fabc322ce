// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// An allocator for large arrays that start as all zeros (the bit grid). Zeroing them with
/// memset costs page faults on one thread before any work starts (docs/why/startup.md); fresh
/// anonymous pages are zero already, so this allocator hands those out untouched (asking for
/// huge pages) and lets the voxelizer's threads fault in only the pages the surface touches.
/// Value-initialising construct() is a no-op because the memory is already zero.
#include <cstddef>
#include <new>
#include <utility>

namespace hyvox {

namespace detail {
void* allocateZeroPages(std::size_t bytes);
void freeZeroPages(void* p, std::size_t bytes);
}  // namespace detail

/// The bytes allocateZeroPages maps for `bytes`: large arrays take whole 2 MiB pages (each one
/// touched is resident whole under THP), so the memory estimate counts what is mapped.
std::size_t zeroPagesMapped(std::size_t bytes) noexcept;

/// Asks for huge pages under [p, p + bytes) (the 2 MiB-aligned part of it) before its pages are
/// first written: each 4 KiB first touch is a page fault, and arrays of millions of triangles
/// spend more time in those faults than in filling them. A hint: without THP it does nothing.
void adviseHugePages(void* p, std::size_t bytes) noexcept;

/// A standard allocator of fresh zero pages (above); stateless, so any two compare equal and
/// one may free what another allocated. Thread-safe.
template <typename T>
struct ZeroPageAllocator {
    using value_type = T;  ///< what it allocates
    ZeroPageAllocator() = default;
    /// Stateless: a copy of any other.
    template <typename U>
    ZeroPageAllocator(const ZeroPageAllocator<U>&) noexcept {}

    /// Zero memory for `n` values (mapped pages for large sizes); throws std::bad_alloc.
    T* allocate(std::size_t n) { return static_cast<T*>(detail::allocateZeroPages(n * sizeof(T))); }
    /// Frees what allocate(n) returned.
    void deallocate(T* p, std::size_t n) noexcept { detail::freeZeroPages(p, n * sizeof(T)); }

    /// Value-initialisation does nothing: the pages are zero already.
    template <typename U>
    void construct(U*) noexcept {}
    /// Any other construction, in place.
    template <typename U, typename... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }

    ///@{
    /// Stateless: all equal.
    template <typename U>
    bool operator==(const ZeroPageAllocator<U>&) const noexcept {
        return true;
    }
    template <typename U>
    bool operator!=(const ZeroPageAllocator<U>&) const noexcept {
        return false;
    }
    ///@}
};

}  // namespace hyvox
