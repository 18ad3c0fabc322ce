// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The winding number of an open mesh brick by brick from a few evaluations, by splitting it
// into an integer part and a smooth part.
//
// c(p), the signed crossings of the ray from p straight down (solid/ray_crossings.h), jumps
// by the same ±1 as w where p passes through the surface, so w - c is continuous across the
// surface. It jumps only on the "sheets" standing above the open edges, where the ray starts or
// stops passing an open edge's face. Closing the surface with every open edge's sheet (the
// strip from the edge, run backwards, up to infinity) makes a surface whose winding number is
// c: w - c = -Σ excess · (the sheets' winding numbers). So for a box of voxels, adding back the
// winding numbers of the sheets that meet it or pass within half its side (each an exact solid
// angle, a few operations) leaves g = -Σ over the other sheets: harmonic, smooth, across the
// surface and around the open edges inside the box alike. Rays up work the same way with
// sheets hanging below the edges; each box takes the direction with fewer sheets.
//
// A box is decided from g at its corners when g at its middle matches the corners'
// interpolation; otherwise it is halved, down to voxels evaluated one by one. A brick's box
// reaches the first voxels of the next bricks, so that its corners lie on the lattice of
// brick corners, each sampled once for the (up to) eight bricks around it: the bricks' boxes'
// corners and middles are evaluated a block of bricks at a time (solid/brick_samples.h). c comes exactly
// from the rays at every voxel, and a voxel whose interpolated w lies near 0.5 is evaluated
// outright (a brick's many such voxels together, the clusters far from all of them as one
// local expansion: FastWinding::atBox, solid/box_winding.cpp). This is a checked
// interpolation, not a bound: the tests compare it with the brute-force winding number on
// open meshes.
#include <array>
#include <cstdint>
#include <memory>

#include "solid/brick_samples.h"
#include "solid/gradient_bound.h"
#include "solid/ray_crossings.h"
#include "solid/winding_less_crossings.h"

namespace hyvox::solid {

class SmoothWinding {
public:
    struct Counters {
        std::uint64_t point_evaluations = 0;    // fast winding numbers evaluated
        std::uint64_t interpolated_voxels = 0;  // voxels decided from the interpolated smooth part
    };
    SmoothWinding(const WindingLessCrossings& winding, const RayCrossings& rays, const GradientBound& bound,
                  const std::array<std::int32_t, 3>& dims);
    ~SmoothWinding();
    // Sets in `inside` the voxels of `wanted` (a brick's bits) whose winding number is at least
    // 0.5; the brick's voxels inside the grid are [lo, hi).
    void decideBrick(const std::array<std::int32_t, 3>& lo, const std::array<std::int32_t, 3>& hi,
                     const std::uint64_t wanted[8], std::uint64_t inside[8], Counters& counters) const;
    // The fast winding numbers the bricks' shared samples took (BrickSamples), all threads'.
    std::uint64_t sampleEvaluations() const { return samples_.evaluations(); }
    // The winding number at voxel (i, j, k)'s centre (off the surface).
    double windingAt(int i, int j, int k) const;

private:
    const WindingLessCrossings& winding_;
    const RayCrossings& rays_;
    const GradientBound& bound_;
    std::array<std::int32_t, 3> dims_;  // the grid's
    BrickSamples samples_;              // the bricks' boxes' corners and middles, shared by the threads
    // The ray columns each thread keeps from brick to brick (smooth_winding.cpp): this
    // object's alone, made per thread on first use and released with it.
    struct ColumnWindows;
    std::unique_ptr<ColumnWindows> windows_;
};

}  // namespace hyvox::solid
