// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// Accuracy of an approximate voxelization against an exact (conservative) one, measured as
/// the point-tessellated voxelization paper does: bias, false voxels, the six-direction
/// ray-marching watertightness test (section 4.1), a flood test of the same, and the γ ↔ bias
/// fit of Eq. 3.
#include <array>
#include <cstdint>
#include <vector>

#include "hyvox/bit_grid.h"
#include "hyvox/grid.h"
#include "hyvox/mesh.h"
#include "hyvox/sparse_grid.h"

namespace hyvox {

/// How an approximate voxelization differs from an exact one.
struct AccuracyReport {
    std::uint64_t reference_voxels = 0;  ///< voxels of the reference
    std::uint64_t missed_voxels = 0;     ///< in the reference, not in the result
    std::uint64_t false_voxels = 0;      ///< in the result, not in the reference
    double bias = 0;                     ///< missed / reference (0 for an empty reference)
};
/// Compares `result` with `reference`, voxel by voxel. The SparseGrid forms (voxelize()
/// results) make both dense first (accuracy is measured at the sizes of tests and benchmarks).
/// Thread-safe (the grids are only read).
/// @throws InvalidInput the grids' dims differ
///@{
AccuracyReport compareToReference(const BitGrid& result, const BitGrid& reference);
AccuracyReport compareToReference(const SparseGrid& result, const SparseGrid& reference);
///@}
/// The result's voxels the reference lacks (to check them one by one, e.g. as touches).
/// @throws InvalidInput the grids' dims differ
///@{
std::vector<std::array<std::int32_t, 3>> falseVoxels(const BitGrid& result, const BitGrid& reference);
std::vector<std::array<std::int32_t, 3>> falseVoxels(const SparseGrid& result, const SparseGrid& reference);
///@}

/// What rayMarchWatertightness() found.
struct WatertightReport {
    std::uint64_t rays = 0;    ///< rays cast (one per voxel column and direction)
    std::uint64_t passed = 0;  ///< of which stopped by the surface they met first
    /// passed / rays (1 without rays).
    double share() const { return rays ? double(passed) / double(rays) : 1.0; }
};
/// Section 4.1's test: rays along +x, -x, +y, -y, +z, -z through the centre of every pixel of
/// the grid's faces, i.e. one ray per voxel column and direction. Each ray is cast against
/// the mesh (double precision) for the point where it first meets the surface; the surface
/// there spans the run of consecutive `conservative` voxels from that point on. A ray passes
/// when the result's first voxel on it comes no later than that run's end, or one voxel past
/// the crossing, whichever is further (so the ray is stopped by the surface it meets first,
/// within one voxel), or when it meets no surface. A ray through a gap runs on to a later
/// surface, or out of the grid, and fails. This is stricter than the paper's "the first voxel
/// hit lies within one voxel of some surface", which a ray through a gap that then hits the
/// back of a closed object would pass.
/// @param result the voxels to test
/// @param conservative the exact conservative voxelization of `mesh` on `grid`
/// @param mesh the mesh both were made from
/// @param grid their grid (the same dims)
///@{
WatertightReport rayMarchWatertightness(const BitGrid& result, const BitGrid& conservative, const ValidatedMesh& mesh,
                                        const GridSpec& grid);
WatertightReport rayMarchWatertightness(const SparseGrid& result, const SparseGrid& conservative,
                                        const ValidatedMesh& mesh, const GridSpec& grid);
///@}

/// What floodFromOutside() found.
struct SealReport {
    std::uint64_t enclosed = 0;                  ///< voxels the exact voxels enclose
    std::uint64_t leaked = 0;                    ///< ... that the flood over the result's empty voxels reaches
    bool sealed() const { return leaked == 0; }  ///< no enclosed voxel reached
};
/// The flood test, independent of the rays: a 6-connected flood from outside the grid over
/// the result's empty voxels must not reach a voxel that the exact voxels enclose (empty there,
/// and cut off from outside by them). Pass the exact *thin* (6-separating) voxels as `exact`:
/// the thicker conservative set also walls off small pockets of outside space between nearby
/// sheets of a surface (docs/why/tessellation-gamma.md), which a thinner result rightly floods.
/// The SparseGrid form makes both dense first.
///@{
SealReport floodFromOutside(const BitGrid& result, const BitGrid& exact);
SealReport floodFromOutside(const SparseGrid& result, const SparseGrid& exact);
///@}

/// Eq. 3: γ = -B · ln(A · p) for the bias p.
struct GammaBiasFit {
    double A = 0;                        ///< Eq. 3's A
    double B = 0;                        ///< Eq. 3's B
    double gammaFor(double bias) const;  ///< Eq. 3
    double biasFor(double gamma) const;  ///< its inverse: p = exp(-γ / B) / A
};
/// Least squares of γ against ln p over the samples (`gammas[n]` gave `biases[n]`).
/// @throws InvalidInput fewer than two distinct biases > 0, or lists of different lengths
GammaBiasFit fitGammaBias(const std::vector<double>& gammas, const std::vector<double>& biases);

}  // namespace hyvox
