// SPDX-License-Identifier: GPL-3.0-or-later
// Built with -fno-math-errno -fno-trapping-math (solid/CMakeLists.txt), for the same reason as
// sheet_sum.cpp: the loop vectorises (-fopt-info-vec reports it). Neither flag changes a result.
#include "solid/solid_angle_sum.h"

#include <algorithm>
#include <cmath>

#include "core/avx2_clones.h"
#include "solid/float_arctangent.h"

namespace hyvox::solid {
namespace {

// atan2(y, x) in [-π, π] by Cephes' atan (a rational function on [0, 0.66], and atan(a) =
// π/4 + atan((a - 1) / (a + 1)) above), from the octant's ratio in [0, 1]; selects, not
// branches.
inline double arctangent2(double y, double x) {
    const double abs_x = std::fabs(x), abs_y = std::fabs(y);
    const double low = std::min(abs_x, abs_y), high = std::max(abs_x, abs_y);
    const double a = low / std::max(high, 1e-300);  // (0, 0) gives 0, as std::atan2 does
    const bool reduce = a > 0.66;
    const double t = reduce ? (a - 1.0) / (a + 1.0) : a;
    const double z = t * t;
    const double p =
        (((-8.750608600031904122785e-1 * z - 1.615753718733365076637e1) * z - 7.500855792314704667340e1) * z -
         1.228866684490136173410e2) *
            z -
        6.485021904942025371773e1;
    const double q =
        ((((z + 2.485846490142306297962e1) * z + 1.650270098316988542046e2) * z + 4.328810604912902668951e2) * z +
         4.853903996359136964868e2) *
            z +
        1.945506571482613964425e2;
    double r = t + t * (z * p / q);
    r = reduce ? r + (M_PI / 4 + 0.5 * 6.123233995736765886130e-17) : r;  // π/4 to 2^-106
    r = abs_y > abs_x ? M_PI / 2 - r : r;
    r = x < 0 ? M_PI - r : r;
    return y < 0 ? -r : r;
}

// tan(Ω/2) of the triangle (a, b, c) seen from q as the pair (y, x) whose atan2 is Ω/2 (Van
// Oosterom & Strackee), from the corners relative to q: u = a - q, v = b - q, w = c - q. One
// formula for both precisions; inline, so each loop below still vectorises.
template <typename Real>
inline void halfSolidAngle(Real ux, Real uy, Real uz, Real vx, Real vy, Real vz, Real wx, Real wy, Real wz, Real& y,
                           Real& x) {
    const Real lu = std::sqrt(ux * ux + uy * uy + uz * uz);
    const Real lv = std::sqrt(vx * vx + vy * vy + vz * vz);
    const Real lw = std::sqrt(wx * wx + wy * wy + wz * wz);
    y = ux * (vy * wz - vz * wy) + uy * (vz * wx - vx * wz) + uz * (vx * wy - vy * wx);
    x = lu * lv * lw + (ux * vx + uy * vy + uz * vz) * lw + (vx * wx + vy * wy + vz * wz) * lu +
        (wx * ux + wy * uy + wz * uz) * lv;
}

}  // namespace

// An AVX2 copy where the platform dispatches by processor (core/avx2_clones.h).
HYVOX_AVX2_CLONES
double solidAngleSum(const TriangleArrays& triangles, std::size_t first, std::size_t count,
                     const std::array<double, 3>& q) {
    const double *ax = triangles.corners[0] + first, *ay = triangles.corners[1] + first,
                 *az = triangles.corners[2] + first, *bx = triangles.corners[3] + first,
                 *by = triangles.corners[4] + first, *bz = triangles.corners[5] + first,
                 *cx = triangles.corners[6] + first, *cy = triangles.corners[7] + first,
                 *cz = triangles.corners[8] + first;
    const double qx = q[0], qy = q[1], qz = q[2];
    // The terms in chunks (a store per term vectorises; a running sum would not without
    // reassociation), summed in order.
    constexpr std::size_t kChunk = 16;
    double sum = 0;
    for (std::size_t start = 0; start < count; start += kChunk) {
        const std::size_t n = std::min(kChunk, count - start);
        double terms[kChunk];
        for (std::size_t k = 0; k < n; ++k) {
            const std::size_t i = start + k;
            double y, x;
            halfSolidAngle(ax[i] - qx, ay[i] - qy, az[i] - qz, bx[i] - qx, by[i] - qy, bz[i] - qz, cx[i] - qx,
                           cy[i] - qy, cz[i] - qz, y, x);
            terms[k] = arctangent2(y, x);
        }
        for (std::size_t k = 0; k < n; ++k) sum += terms[k];
    }
    return sum / (2.0 * M_PI);  // Ω = 2 atan2(...), over 4π
}

HYVOX_AVX2_CLONES
double solidAngleSum(const FloatTriangleArrays& triangles, std::size_t count, const std::array<float, 3>& q) {
    const float *ax = triangles.corners[0], *ay = triangles.corners[1], *az = triangles.corners[2],
                *bx = triangles.corners[3], *by = triangles.corners[4], *bz = triangles.corners[5],
                *cx = triangles.corners[6], *cy = triangles.corners[7], *cz = triangles.corners[8];
    const float qx = q[0], qy = q[1], qz = q[2];
    constexpr std::size_t kChunk = 32;
    double sum = 0;
    for (std::size_t start = 0; start < count; start += kChunk) {
        const std::size_t n = std::min(kChunk, count - start);
        float terms[kChunk];
        for (std::size_t k = 0; k < n; ++k) {
            const std::size_t i = start + k;
            float y, x;
            halfSolidAngle(ax[i] - qx, ay[i] - qy, az[i] - qz, bx[i] - qx, by[i] - qy, bz[i] - qz, cx[i] - qx,
                           cy[i] - qy, cz[i] - qz, y, x);
            terms[k] = floats::arctangent2(y, x);
        }
        float chunk = 0;
        for (std::size_t k = 0; k < n; ++k) chunk += terms[k];
        sum += chunk;
    }
    return sum / (2.0 * M_PI);  // Ω = 2 atan2(...), over 4π
}

}  // namespace hyvox::solid
