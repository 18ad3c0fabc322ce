// SPDX-License-Identifier: GPL-3.0-or-later
#include "cpu/rasterize_small.h"

#include <cstdint>

#include "core/avx2_clones.h"

// The helpers below pass 32-byte vectors by value; they are internal and inlined, so the
// calling convention GCC warns about (AVX registers or memory) never applies.
#if defined(__GNUC__)  // GCC and clang
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace hyvox::cpu {
namespace {

// Four lanes (GCC / clang vector extensions: AVX2 registers in the AVX2 copy below, pairs of
// SSE2 registers otherwise). Each lane's arithmetic is the scalar expression of
// rasterize_triangle.h, operation for operation (no FMA), so every lane rounds alike.
typedef double Doubles __attribute__((vector_size(32)));
typedef std::int64_t Masks __attribute__((vector_size(32)));  // per lane: all ones (true) or 0
typedef std::int32_t Ints __attribute__((vector_size(16)));

__attribute__((always_inline)) inline Doubles splat(double x) { return Doubles{x, x, x, x}; }
__attribute__((always_inline)) inline Ints splatInt(int x) { return Ints{x, x, x, x}; }
__attribute__((always_inline)) inline Doubles select(Masks m, Doubles yes, Doubles no) {
    return Doubles((m & Masks(yes)) | (~m & Masks(no)));
}

// clampCoord, floorToInt and ceilToInt (clamp_coord.h, triangle_setup.h) per lane: the same
// truncation to int and the same comparison against it.
__attribute__((always_inline)) inline Doubles clampCoords(Doubles x) {
    return select(x < splat(-1.0e9), splat(-1.0e9), select(x > splat(1.0e9), splat(1.0e9), x));
}
__attribute__((always_inline)) inline Ints floorToInts(Doubles x) {
    const Ints i = __builtin_convertvector(x, Ints);
    return i + __builtin_convertvector(x < __builtin_convertvector(i, Doubles), Ints);  // a true lane is -1
}
__attribute__((always_inline)) inline Ints ceilToInts(Doubles x) {
    const Ints i = __builtin_convertvector(x, Ints);
    return i - __builtin_convertvector(x > __builtin_convertvector(i, Doubles), Ints);
}

// The NU x NV x NW candidates from t.lo; lane l of step k holds the column (du, dv) with
// du * NV + dv = 4k + l of the dominant plane, and the depth loop runs over its NW voxels.
template <int NU, int NV, int NW>
__attribute__((always_inline)) inline std::uint64_t acceptedFixed(const TriangleSetup& t) {
    constexpr int kColumns = NU * NV;
    const double nu = t.normal[0], nv = t.normal[1], inv_nw = 1.0 / t.normal[2];
    const double ou = t.origin[0], ov = t.origin[1], ow = t.origin[2];
    static_assert(NU <= kSmallSide && NV <= kSmallSide && NW <= kSmallSide, "bits of a small triangle");
    // The answer is in grid order: a step along u, v or w moves smallBoxBit by that of its axis.
    const int axis_step[3] = {smallBoxBit(1, 0, 0), smallBoxBit(0, 1, 0), smallBoxBit(0, 0, 1)};
    const int u_step = axis_step[t.w == 2 ? 0 : t.w + 1], v_step = axis_step[t.w == 0 ? 2 : t.w - 1],
              w_step = axis_step[t.w];
    Masks accepted{0, 0, 0, 0};
    for (int k = 0; 4 * k < kColumns; ++k) {
        auto du = [&](int l) { return 4 * k + l < kColumns ? (4 * k + l) / NV : 0; };
        auto dv = [&](int l) { return 4 * k + l < kColumns ? (4 * k + l) % NV : 0; };
        auto real = [&](int l) { return 4 * k + l < kColumns ? std::int64_t(-1) : std::int64_t(0); };
        const Doubles pu = __builtin_convertvector(splatInt(t.lo[0]) + Ints{du(0), du(1), du(2), du(3)}, Doubles);
        const Doubles pv = __builtin_convertvector(splatInt(t.lo[1]) + Ints{dv(0), dv(1), dv(2), dv(3)}, Doubles);
        // The dominant plane's edge tests: the column's 2D test.
        Masks column{real(0), real(1), real(2), real(3)};
        for (int i = 0; i < 3; ++i) {
            const EdgeTest& e = t.uv[i];
            const Doubles uv_row = splat(e.nb) * (pv - splat(e.vb)) + splat(e.offset);
            column &= splat(e.na) * (pu - splat(e.va)) + uv_row >= splat(0.0);
        }
        // The depth range of the column, and the per-row / per-column parts of the other two
        // projections' tests.
        const Doubles d = splat(nu) * (pu - splat(ou)) + splat(nv) * (pv - splat(ov));
        const Ints w0 = ceilToInts(clampCoords(splat(ow) - (d + splat(t.depth_lo_offset)) * splat(inv_nw))) - 1;
        const Ints w1 = floorToInts(clampCoords(splat(ow) - (d + splat(t.depth_hi_offset)) * splat(inv_nw)));
        // Each lane's bit of the answer (smallBoxBit in grid order) at dw = 0.
        const Masks lane_bits = Masks{1, 1, 1, 1}
            << (Masks{du(0), du(1), du(2), du(3)} * u_step + Masks{dv(0), dv(1), dv(2), dv(3)} * v_step);
        Doubles vw_row[3], wu_col[3];
        for (int i = 0; i < 3; ++i) {
            vw_row[i] = splat(t.vw[i].na) * (pv - splat(t.vw[i].va)) + splat(t.vw[i].offset);
            wu_col[i] = splat(t.wu[i].nb) * (pu - splat(t.wu[i].vb)) + splat(t.wu[i].offset);
        }
        for (int dw = 0; dw < NW; ++dw) {
            const int pw = t.lo[2] + dw;
            const double pwd = pw;
            Masks inside = column & __builtin_convertvector((splatInt(pw) >= w0) & (splatInt(pw) <= w1), Masks);
            for (int i = 0; i < 3; ++i) {
                inside &= splat(t.vw[i].nb * (pwd - t.vw[i].vb)) + vw_row[i] >= splat(0.0);
                inside &= splat(t.wu[i].na * (pwd - t.wu[i].va)) + wu_col[i] >= splat(0.0);
            }
            accepted |= inside & (lane_bits << (dw * w_step));
        }
    }
    return std::uint64_t(accepted[0] | accepted[1] | accepted[2] | accepted[3]);
}

// An AVX2 copy where the platform dispatches by processor (core/avx2_clones.h): four lanes a
// step instead of two. Its own name: the header's inline rasterizeSmall uses the public one
// before this file could define it, and clang builds clones only of a function not yet used.
HYVOX_AVX2_CLONES
std::uint64_t acceptedCandidates(const TriangleSetup& t) {
    // One instance per candidate count along each axis (1 to 4): a triangle that lies within
    // one voxel's range along one axis tests half the voxels a 2 x 2 x 2 one does.
#define HYVOX_SIZE(NU, NV, NW) \
    case smallBoxBit((NU) - 1, (NV) - 1, (NW) - 1): return acceptedFixed<NU, NV, NW>(t);
#define HYVOX_SIZES_W(NU, NV) HYVOX_SIZE(NU, NV, 1) HYVOX_SIZE(NU, NV, 2) HYVOX_SIZE(NU, NV, 3) HYVOX_SIZE(NU, NV, 4)
#define HYVOX_SIZES_VW(NU) HYVOX_SIZES_W(NU, 1) HYVOX_SIZES_W(NU, 2) HYVOX_SIZES_W(NU, 3) HYVOX_SIZES_W(NU, 4)
    static_assert(kSmallSide == 4, "one case per size below");
    switch (smallBoxBit(t.hi[0] - t.lo[0], t.hi[1] - t.lo[1], t.hi[2] - t.lo[2])) {
        HYVOX_SIZES_VW(1)
        HYVOX_SIZES_VW(2)
        HYVOX_SIZES_VW(3)
        HYVOX_SIZES_VW(4)
        default: return 0;  // not a small triangle (fitsSmallPath)
    }
#undef HYVOX_SIZES_VW
#undef HYVOX_SIZES_W
#undef HYVOX_SIZE
}

}  // namespace

std::uint64_t acceptedSmallCandidates(const TriangleSetup& t) { return acceptedCandidates(t); }

}  // namespace hyvox::cpu
