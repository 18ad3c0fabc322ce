// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The far field of many clusters of triangles, seen from one small box, as one polynomial
// about the box's centre q0 (a local expansion, as in the fast multipole method): the work per
// cluster is done once for the box, and each point of the box then costs a polynomial.
//
// A cluster's far field in the fast winding numbers (solid/fast_winding.h), times 4π, at q,
// with r = c - q and G(q) = 1/|c - q|:
//     F(q) = A·r/|r|³ + tr M/|r|³ - 3 rᵀM r/|r|⁵ = Σ_i A_i ∂_i G - Σ_ij M_ij ∂_i ∂_j G
// (∂ along q; A the area vector, M the first moment; only M's symmetric part matters). With
// δ = q - q0, R = c - q0 and b_k the Taylor coefficients of G about q0 (multi-index k,
// G(q0 + δ) = 1/|R - δ| = Σ_k b_k δ^k), the Taylor series of F is
//     F(q0 + δ) = Σ_α L_α δ^α,  L_α = Σ_i A_i (α_i + 1) b_{α+e_i} - Σ_ij M_ij c_ij(α) b_{α+e_i+e_j}
// with c_ij(α) = (α_i + 1)(α_j + 1) for i ≠ j and (α_i + 1)(α_i + 2) for i = j, and the b_k
// follow from b_0 = 1/|R| by the recurrence of the Taylor coefficients of 1/|R - δ|
// (Duan & Krasny 2001; Lindsay & Krasny 2001):
//     |k| |R|² b_k = (2|k| - 1) Σ_i R_i b_{k-e_i} - (|k| - 1) Σ_i b_{k-2e_i}.
// The series is cut after order 3 in δ. The terms of order n are about (|δ| / |R|)^n of the
// first, so for points within ρ of q0 and clusters farther than κρ the part cut off is about
// (1/κ)^4 of the cluster's field (κ = 3 in FastWinding::atBox: 1/81;
// tests/native/test_solid.cpp compares the polynomial with the clusters' fields summed point
// by point).
//
// The clusters are taken in batches, structure of arrays, so that the recurrence vectorises
// across clusters.
#include <array>
#include <cstddef>

namespace hyvox::solid {

class LocalExpansion {
public:
    using Vec3 = std::array<double, 3>;
    static constexpr int kOrder = 3;
    static constexpr int kTerms = 20;  // monomials δ^α with |α| <= 3
    static constexpr int kBatch = 32;  // clusters per batch

    // Starts an empty expansion about `centre`.
    void reset(const Vec3& centre);
    // Adds a cluster's far field (its area-weighted centre, area vector and first moment, as
    // moment[3 i + j] = Σ area_i (centroid - centre)_j; null for none, as for one triangle
    // about its own centroid). The cluster must lie well away from the centre (see above).
    void add(const Vec3& cluster_centre, const Vec3& area, const std::array<double, 9>* moment);
    // Σ over the clusters added of F(q), times 4π as above.
    double at(const Vec3& q);

private:
    void flush();  // the pending batch into the coefficients

    Vec3 centre_{};
    int pending_ = 0;
    // The pending batch: R = c - q0, A, and M's symmetric part (xx, yy, zz, xy, xz, yz).
    alignas(64) double r_[3][kBatch];
    alignas(64) double a_[3][kBatch];
    alignas(64) double m_[6][kBatch];
    // Per coefficient and lane, summed over the batches (summed across lanes once, in order).
    alignas(64) double lanes_[kTerms][kBatch];
    std::array<double, kTerms> coefficients_{};
    bool summed_ = true;
};

}  // namespace hyvox::solid
