// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// HYVOX_AVX2_CLONES before a function builds it twice on x86-64 Linux, for AVX2 and for the
// baseline, the copy the processor runs chosen when the binary loads (GNU ifunc): its loops run
// twice as wide. Same operations in the same order and no FMA, so both copies give the same
// bits. GCC, and clang from 16 (clang 14 emitted no symbol for a member function's clones);
// the resolver reads the runtime's CPU model, which hyvox brings itself where the runtime has
// none (os/cpu_model_fallback.c, zig's), and which a platform without ifunc lacks
// (HYVOX_NO_TARGET_CLONES, CMakeLists.txt). With clang, a function built as clones must be
// defined before its first use in its file.
//
// HYVOX_AVX2_CLONES_GCC: the same, with GCC only, for a function that calls inline functions
// it does not inline (oneTBB's, a constructor): clang emits no copy of an inline function
// that only a clone calls, and the link fails.
#if defined(__x86_64__) && defined(__linux__) && !defined(HYVOX_NO_TARGET_CLONES)
#if !defined(__clang__)
#define HYVOX_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#define HYVOX_AVX2_CLONES_GCC __attribute__((target_clones("avx2", "default")))
#elif __clang_major__ >= 16
#define HYVOX_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#endif
#endif
#ifndef HYVOX_AVX2_CLONES
#define HYVOX_AVX2_CLONES
#endif
#ifndef HYVOX_AVX2_CLONES_GCC
#define HYVOX_AVX2_CLONES_GCC
#endif
