// SPDX-License-Identifier: GPL-3.0-or-later
// Built with -fno-math-errno -fno-trapping-math (solid/CMakeLists.txt), as sheet_sum.cpp: the
// loops over a batch's clusters vectorise. Neither flag changes a result.
#include "solid/local_expansion.h"

#include <cmath>

#include "core/avx2_clones.h"

namespace hyvox::solid {
namespace {

// The multi-indices k with |k| <= kDerivatives (b_k is needed up to order 3 + 2: the second
// derivatives of G in the moment term), by order, and for each the rows of k - e_i, k - 2 e_i
// and k + e_i (kZero, a row of zeros, where the index would leave the table).
constexpr int kDerivatives = LocalExpansion::kOrder + 2;
constexpr int kRows = (kDerivatives + 1) * (kDerivatives + 2) * (kDerivatives + 3) / 6;  // 56
constexpr int kZero = kRows;

struct Tables {
    int k[kRows][3] = {};
    int order[kRows] = {};
    int minus1[kRows][3] = {}, minus2[kRows][3] = {}, plus1[kRows][3] = {};
};

constexpr int rowOf(const Tables& t, int a, int b, int c) {
    if (a < 0 || b < 0 || c < 0 || a + b + c > kDerivatives) return kZero;
    for (int n = 0; n < kRows; ++n)
        if (t.k[n][0] == a && t.k[n][1] == b && t.k[n][2] == c) return n;
    return kZero;
}

constexpr Tables makeTables() {
    Tables t;
    int n = 0;
    for (int o = 0; o <= kDerivatives; ++o)
        for (int a = o; a >= 0; --a)
            for (int b = o - a; b >= 0; --b) {
                t.k[n][0] = a, t.k[n][1] = b, t.k[n][2] = o - a - b;
                t.order[n++] = o;
            }
    for (int m = 0; m < kRows; ++m)
        for (int i = 0; i < 3; ++i) {
            int k[3] = {t.k[m][0], t.k[m][1], t.k[m][2]};
            k[i] -= 1;
            t.minus1[m][i] = rowOf(t, k[0], k[1], k[2]);
            k[i] -= 1;
            t.minus2[m][i] = rowOf(t, k[0], k[1], k[2]);
            k[i] += 3;
            t.plus1[m][i] = rowOf(t, k[0], k[1], k[2]);
        }
    return t;
}

constexpr Tables kTables = makeTables();
static_assert(kTables.order[LocalExpansion::kTerms - 1] == LocalExpansion::kOrder &&
              kTables.order[LocalExpansion::kTerms] == LocalExpansion::kOrder + 1);

}  // namespace

void LocalExpansion::reset(const Vec3& centre) {
    centre_ = centre;
    pending_ = 0;
    for (auto& row : lanes_)
        for (double& lane : row) lane = 0.0;
    coefficients_.fill(0.0);
    summed_ = true;
}

// An AVX2 copy where the platform dispatches by processor (core/avx2_clones.h).
HYVOX_AVX2_CLONES
void LocalExpansion::flush() {
    // Unused lanes: a cluster of no area one unit away (finite terms, all zero in the end).
    for (int j = pending_; j < kBatch; ++j) {
        r_[0][j] = 1.0, r_[1][j] = r_[2][j] = 0.0;
        for (auto& row : a_) row[j] = 0.0;
        for (auto& row : m_) row[j] = 0.0;
    }
    pending_ = 0;
    alignas(64) double b[kRows + 1][kBatch];
    alignas(64) double inverse_r2[kBatch];
    for (int j = 0; j < kBatch; ++j) {
        const double r2 = r_[0][j] * r_[0][j] + r_[1][j] * r_[1][j] + r_[2][j] * r_[2][j];
        inverse_r2[j] = 1.0 / r2;
        b[0][j] = 1.0 / std::sqrt(r2);
        b[kZero][j] = 0.0;
    }
    for (int n = 1; n < kRows; ++n) {
        const double o = kTables.order[n];
        const double c1 = (2.0 * o - 1.0) / o, c2 = (o - 1.0) / o;
        const double *x1 = b[kTables.minus1[n][0]], *y1 = b[kTables.minus1[n][1]], *z1 = b[kTables.minus1[n][2]];
        const double *x2 = b[kTables.minus2[n][0]], *y2 = b[kTables.minus2[n][1]], *z2 = b[kTables.minus2[n][2]];
        double* out = b[n];
        for (int j = 0; j < kBatch; ++j)
            out[j] = (c1 * (r_[0][j] * x1[j] + r_[1][j] * y1[j] + r_[2][j] * z1[j]) - c2 * (x2[j] + y2[j] + z2[j])) *
                inverse_r2[j];
    }
    for (int n = 0; n < kTerms; ++n) {
        const int* k = kTables.k[n];
        const int* up = kTables.plus1[n];
        // A's rows and factors, then M's: the diagonal (k + 2 e_i) and, doubled for the
        // symmetric pair, xy, xz, yz.
        const double fa[3] = {k[0] + 1.0, k[1] + 1.0, k[2] + 1.0};
        const double fm[6] = {(k[0] + 1.0) * (k[0] + 2.0),       (k[1] + 1.0) * (k[1] + 2.0),
                              (k[2] + 1.0) * (k[2] + 2.0),       2.0 * (k[0] + 1.0) * (k[1] + 1.0),
                              2.0 * (k[0] + 1.0) * (k[2] + 1.0), 2.0 * (k[1] + 1.0) * (k[2] + 1.0)};
        const double *ax = b[up[0]], *ay = b[up[1]], *az = b[up[2]];
        const double *mxx = b[kTables.plus1[up[0]][0]], *myy = b[kTables.plus1[up[1]][1]],
                     *mzz = b[kTables.plus1[up[2]][2]];
        const double *mxy = b[kTables.plus1[up[0]][1]], *mxz = b[kTables.plus1[up[0]][2]],
                     *myz = b[kTables.plus1[up[1]][2]];
        double* lane = lanes_[n];
        for (int j = 0; j < kBatch; ++j) {
            const double dipole = a_[0][j] * fa[0] * ax[j] + a_[1][j] * fa[1] * ay[j] + a_[2][j] * fa[2] * az[j];
            const double moment = m_[0][j] * fm[0] * mxx[j] + m_[1][j] * fm[1] * myy[j] + m_[2][j] * fm[2] * mzz[j] +
                m_[3][j] * fm[3] * mxy[j] + m_[4][j] * fm[4] * mxz[j] + m_[5][j] * fm[5] * myz[j];
            lane[j] += dipole - moment;
        }
    }
}

// After flush(): a function built as clones is defined before its first use (clang).
void LocalExpansion::add(const Vec3& cluster_centre, const Vec3& area, const std::array<double, 9>* moment) {
    const int j = pending_;
    for (int d = 0; d < 3; ++d) {
        r_[d][j] = cluster_centre[d] - centre_[d];
        a_[d][j] = area[d];
    }
    if (moment) {
        const auto& m = *moment;
        m_[0][j] = m[0], m_[1][j] = m[4], m_[2][j] = m[8];
        m_[3][j] = 0.5 * (m[1] + m[3]), m_[4][j] = 0.5 * (m[2] + m[6]), m_[5][j] = 0.5 * (m[5] + m[7]);
    } else {
        for (auto& row : m_) row[j] = 0.0;
    }
    summed_ = false;
    if (++pending_ == kBatch) flush();
}

double LocalExpansion::at(const Vec3& q) {
    if (!summed_) {
        if (pending_ > 0) flush();
        for (int n = 0; n < kTerms; ++n) {
            double sum = 0;
            for (const double lane : lanes_[n]) sum += lane;
            coefficients_[std::size_t(n)] = sum;
        }
        summed_ = true;
    }
    double powers[3][kOrder + 1];
    for (int d = 0; d < 3; ++d) {
        powers[d][0] = 1.0;
        for (int e = 1; e <= kOrder; ++e) powers[d][e] = powers[d][e - 1] * (q[d] - centre_[d]);
    }
    double value = 0;
    for (int n = 0; n < kTerms; ++n)
        value += coefficients_[std::size_t(n)] * powers[0][kTables.k[n][0]] * powers[1][kTables.k[n][1]] *
            powers[2][kTables.k[n][2]];
    return value;
}

}  // namespace hyvox::solid
