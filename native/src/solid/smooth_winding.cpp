// SPDX-License-Identifier: GPL-3.0-or-later
#include "solid/smooth_winding.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "hyvox/bit_grid.h"
#include "solid/sheet_sum.h"

namespace hyvox::solid {
namespace {

// The middle of a box may differ from the corners' interpolation by this much for the box to
// be interpolated (the fast winding numbers themselves are off by up to about 0.01).
constexpr double kAgree = 0.02;
// Voxels whose interpolated winding number lies closer to 0.5 than this are evaluated outright.
constexpr double kMargin = 0.06;
// The sheets of open edges this many box sides from a box are taken out of its smooth part.
constexpr double kNearSides = 0.5;
// A brick's voxels evaluated outright share the clusters far from all of them (one walk of the
// tree for the box, FastWinding::atBox) when there are at least this many. Even two pay: the
// walk shared by two voxels costs less than two walks (docs/why/solid.md).
constexpr std::size_t kSharedFarField = 2;

using Int3 = std::array<std::int32_t, 3>;

// A brick's columns' crossings (the rays' columns [i0, i0 + ni) × [j0, j0 + nj)), as the rays
// give them, and their heights sorted, with the signed counts below each.
struct ColumnBlock {
    std::array<int, 4> key{-1, -1, -1, -1};              // {i0, j0, ni, nj}; none yet
    std::vector<RayCrossings::Crossing> columns[9 * 9];  // no allocation per brick once grown
    std::vector<double> heights[9 * 9];  // the crossings' heights (NaN left out: below no centre), ascending
    std::vector<int> prefix[9 * 9];      // prefix[m]: the signed crossings of the lowest m
    int total[9 * 9];                    // C, NaN heights included
};

// The crossings of a block of columns are whole lines: the same for every brick of a stack
// along z. Each thread keeps the blocks of its recent bricks, one slot per brick column (x
// and y modulo 16): the octree's order visits the bricks of a 16×16 window of columns before
// it moves on, and comes back to each for the next bricks along z, which a cache of the last
// few blocks has lost by then (docs/why/solid.md). A block is found there before the rays are
// asked (the blocks are the same whichever thread finds them). One window per thread and per
// SmoothWinding: released with the call, never another call's.
class ColumnWindow {
public:
    const ColumnBlock& columnsOf(const RayCrossings& rays, int i0, int j0, int ni, int nj) {
        const std::array<int, 4> key{i0, j0, ni, nj};
        ColumnBlock& block = blocks_[std::size_t(((i0 >> 3) % kWindow) * kWindow + (j0 >> 3) % kWindow)];
        if (block.key == key) return block;
        // Marked as no block's while it is refilled: an exception half way (no memory) must
        // not leave the previous key on half-new columns.
        block.key = {-1, -1, -1, -1};
        rays.columns(i0, j0, ni, nj, block.columns);
        for (int n = 0; n < ni * nj; ++n) {
            block.total[n] = 0;
            sorted_.clear();
            for (const auto& c : block.columns[n]) {
                block.total[n] += c.sign;
                if (!std::isnan(c.z)) sorted_.push_back(c);
            }
            std::sort(sorted_.begin(), sorted_.end(), [](const auto& a, const auto& b) { return a.z < b.z; });
            block.heights[n].resize(sorted_.size());
            block.prefix[n].resize(sorted_.size() + 1);
            block.prefix[n][0] = 0;
            for (std::size_t m = 0; m < sorted_.size(); ++m) {
                block.heights[n][m] = sorted_[m].z;
                block.prefix[n][m + 1] = block.prefix[n][m] + sorted_[m].sign;
            }
        }
        block.key = key;
        return block;
    }

private:
    static constexpr int kWindow = 16;
    std::vector<ColumnBlock> blocks_ = std::vector<ColumnBlock>(kWindow * kWindow);
    std::vector<RayCrossings::Crossing> sorted_;
};

// One brick's rays and samples, over the brick's voxels and the next voxel along each axis
// (the corners the brick shares with its neighbours).
class Brick {
public:
    // The voxels [lo, top] (top at most lo + 8).
    Brick(const WindingLessCrossings& winding, const RayCrossings& rays, ColumnWindow& window,
          const BrickSamples& shared, const Int3& lo, const Int3& top, SmoothWinding::Counters& counters)
        : winding_(winding), rays_(rays), window_(window), shared_(shared), lo_(lo), top_(top), counters_(counters) {
        std::fill(std::begin(samples_), std::end(samples_), NAN);
    }

    // w - c at voxel p's centre (sampled just above it). The corners and middles of the
    // bricks' boxes come from the shared samples (BrickSamples), the same for every brick.
    double minusCrossings(const Int3& p) {
        sample(&p, 1);
        return samples_[local(p)];
    }
    // minusCrossings() of `count` points (at most 9), those not yet known evaluated together
    // (one walk of the tree: FastWinding::atMany, equal to at() bit for bit).
    void sample(const Int3* points, int count) {
        Vec3 lifted[9];
        int wanted[9], below[9];
        int n = 0;
        for (int q = 0; q < count; ++q) {
            const Int3& p = points[q];
            double& cached = samples_[local(p)];
            if (!std::isnan(cached) || std::find(wanted, wanted + n, local(p)) != wanted + n) continue;
            if (shared_.find(p, cached)) continue;
            const Column& column = columnOf(p);
            lifted[n] = {p[0] + 0.5, p[1] + 0.5, sampleHeight(column, p[2] + 0.5)};
            below[n] = crossingsBelow(column, lifted[n][2]);
            wanted[n++] = local(p);
        }
        if (n == 0) return;
        counters_.point_evaluations += std::uint64_t(n);
        double w[9];
        winding_.at(lifted, below, std::size_t(n), false, w);
        for (int q = 0; q < n; ++q) samples_[wanted[q]] = w[q];
    }
    bool sampled(const Int3& p) const { return !std::isnan(samples_[local(p)]); }
    // The signed crossings below voxel p's centre, and C, those of the whole line (from the
    // columns' tables: every voxel of a column asks).
    int crossings(const Int3& p) {
        columnOf(p);
        return below_[column(p)][p[2] - lo_[2]];
    }
    int columnCrossings(const Int3& p) {
        columnOf(p);
        return block_->total[column(p)];
    }
    // The winding numbers at the centres of `voxels`, into `out`, together.
    void exactWindings(const std::vector<Int3>& voxels, std::vector<double>& out) {
        counters_.point_evaluations += voxels.size();
        centres_.resize(voxels.size());
        below_centres_.resize(voxels.size());
        for (std::size_t n = 0; n < voxels.size(); ++n) {
            centres_[n] = {voxels[n][0] + 0.5, voxels[n][1] + 0.5, voxels[n][2] + 0.5};
            below_centres_[n] = crossings(voxels[n]);
        }
        out.resize(voxels.size());
        // Enough of them, and one walk of the tree for the box pays (FastWinding::atBox);
        // the choice depends on the brick alone, never on the threads.
        winding_.at(centres_.data(), below_centres_.data(), centres_.size(), voxels.size() >= kSharedFarField,
                    out.data());
        for (std::size_t n = 0; n < voxels.size(); ++n) out[n] += below_centres_[n];
    }

private:
    using Column = std::vector<RayCrossings::Crossing>;
    int local(const Int3& p) const { return ((p[0] - lo_[0]) * 9 + (p[1] - lo_[1])) * 9 + (p[2] - lo_[2]); }
    int column(const Int3& p) const { return (p[0] - lo_[0]) * (top_[1] - lo_[1] + 1) + (p[1] - lo_[1]); }
    // The rays of all the brick's columns are found together, on first use, with each
    // column's crossings below the brick's voxel centres (the same comparisons as
    // crossingsBelow(), on the block's sorted heights).
    const Column& columnOf(const Int3& p) {
        if (!block_) {
            const int ni = top_[0] - lo_[0] + 1, nj = top_[1] - lo_[1] + 1, nz = top_[2] - lo_[2] + 1;
            block_ = &window_.columnsOf(rays_, lo_[0], lo_[1], ni, nj);
            for (int n = 0; n < ni * nj; ++n) {
                const std::vector<double>& heights = block_->heights[n];
                const std::vector<int>& prefix = block_->prefix[n];
                std::size_t m =
                    std::size_t(std::lower_bound(heights.begin(), heights.end(), lo_[2] + 0.5) - heights.begin());
                for (int k = 0; k < nz; ++k) {
                    while (m < heights.size() && heights[m] < lo_[2] + k + 0.5) ++m;
                    below_[n][k] = prefix[m];
                }
            }
        }
        return block_->columns[column(p)];
    }

    const WindingLessCrossings& winding_;
    const RayCrossings& rays_;
    ColumnWindow& window_;  // this thread's
    const BrickSamples& shared_;
    Int3 lo_, top_;
    SmoothWinding::Counters& counters_;
    const ColumnBlock* block_ = nullptr;  // the brick's columns, in the window
    int below_[9 * 9][9];                 // per column, the signed crossings below each of the brick's centres
    std::vector<Vec3> centres_;
    std::vector<int> below_centres_;
    double samples_[9 * 9 * 9];  // w - c; NaN: not sampled
};

}  // namespace

struct SmoothWinding::ColumnWindows {
    tbb::enumerable_thread_specific<ColumnWindow> per_thread;  // made on a thread's first brick
};

SmoothWinding::SmoothWinding(const WindingLessCrossings& winding, const RayCrossings& rays, const GradientBound& bound,
                             const std::array<std::int32_t, 3>& dims)
    : winding_(winding),
      rays_(rays),
      bound_(bound),
      dims_(dims),
      samples_(winding, rays, dims),
      windows_(std::make_unique<ColumnWindows>()) {}

SmoothWinding::~SmoothWinding() = default;

double SmoothWinding::windingAt(int i, int j, int k) const {
    const Vec3 centre{i + 0.5, j + 0.5, k + 0.5};
    const int below = rays_.at(i, j, k);
    double less;
    winding_.at(&centre, &below, 1, false, &less);
    return below + less;
}

void SmoothWinding::decideBrick(const std::array<std::int32_t, 3>& lo, const std::array<std::int32_t, 3>& hi,
                                const std::uint64_t wanted[8], std::uint64_t inside[8], Counters& counters) const {
    // The brick and, where the grid goes on, the first voxels of the next bricks: the corners
    // are then lattice points, each sampled once for the eight bricks around it.
    Int3 top;
    for (int d = 0; d < 3; ++d) top[d] = hi[d] == lo[d] + 8 && hi[d] < dims_[d] ? hi[d] : hi[d] - 1;
    Brick brick(winding_, rays_, windows_->per_thread.local(), samples_, lo, top, counters);
    std::uint64_t done[8] = {};
    auto bit = [](const Int3& p) { return BitGrid::bitInBrick(p[0], p[1], p[2]); };
    auto pending = [&](const Int3& p) {
        if (p[0] >= hi[0] || p[1] >= hi[1] || p[2] >= hi[2]) return std::uint64_t(0);  // the next brick's
        const int n = bit(p);
        return ((wanted[n >> 6] & ~done[n >> 6]) >> (n & 63)) & 1;
    };
    auto decide = [&](const Int3& p, double w) {
        const int n = bit(p);
        done[n >> 6] |= std::uint64_t(1) << (n & 63);
        if (w >= 0.5) inside[n >> 6] |= std::uint64_t(1) << (n & 63);
    };
    // Voxels whose interpolated winding number lies near 0.5: evaluated outright, together,
    // once the boxes are done (marked done now, so that a box sharing them skips them).
    std::vector<Int3> outright;
    std::vector<double> outright_values;
    auto defer = [&](const Int3& p) {
        const int n = bit(p);
        done[n >> 6] |= std::uint64_t(1) << (n & 63);
        outright.push_back(p);
    };
    auto forEach = [](const Int3& a, const Int3& b, auto&& f) {
        for (int i = a[0]; i <= b[0]; ++i)
            for (int j = a[1]; j <= b[1]; ++j)
                for (int k = a[2]; k <= b[2]; ++k) f(Int3{i, j, k});
    };
    std::vector<GradientBound::Sheet> sheets, sheets_up;
    SheetSum sheet_sum;

    // The pending voxels of column (i, j) of box [a, b] (inside the brick: the next bricks'
    // voxels are never pending), one bit per z from a[2].
    auto pendingColumn = [&](int i, int j, const Int3& a, const Int3& b) {
        const int z_end = std::min(b[2], hi[2] - 1);
        if (i >= hi[0] || j >= hi[1] || z_end < a[2]) return 0u;
        const int x = i & 7;
        const unsigned row = unsigned((wanted[x] & ~done[x]) >> ((j & 7) * 8)) & 0xffu;
        return (row >> (a[2] & 7)) & ((2u << (z_end - a[2])) - 1u);
    };
    // Boxes of voxels [a, b] (corners included), halved where interpolation does not hold.
    auto visit = [&](auto&& self, const Int3& a, const Int3& b) -> void {
        bool any = false;
        for (int i = a[0]; i <= b[0] && !any; ++i)
            for (int j = a[1]; j <= b[1] && !any; ++j) any = pendingColumn(i, j, a, b) != 0;
        if (!any) return;
        if (b[0] - a[0] <= 1 && b[1] - a[1] <= 1 && b[2] - a[2] <= 1) {
            // Every voxel is a corner: each evaluated.
            forEach(a, b, [&](const Int3& p) {
                if (pending(p)) decide(p, brick.crossings(p) + brick.minusCrossings(p));
            });
            return;
        }
        // The sheets meeting the box, and those of the edges near it: without them g would
        // vary fast near the box's sides (any set of sheets that holds those leaves g smooth).
        int side = 0;
        for (int d = 0; d < 3; ++d) side = std::max(side, b[d] - a[d] + 1);
        // Rays down or up, whichever has fewer sheets here: w - c_down = -Σ sheets above edges
        // and w - c_down + C = -Σ sheets below them (the rays up see C - c_down crossings, of
        // the other sign).
        const double reach = kNearSides * side;
        const Box near{{a[0] - reach, a[1] - reach, a[2] - reach},
                       {b[0] + 1.0 + reach, b[1] + 1.0 + reach, b[2] + 1.0 + reach}};
        bound_.sheetsMeeting(near, sheets, sheets_up);
        const bool upward = sheets_up.size() < sheets.size();
        if (upward) std::swap(sheets, sheets_up);
        sheet_sum.assign(sheets, upward, {double(a[0]), double(a[1]), double(a[2])});
        auto shift = [&](const Int3& p) { return upward ? brick.columnCrossings(p) : 0; };
        // NaN where a voxel's column passes (nearly) through an edge: not interpolated.
        auto sheetSum = [&](const Int3& p) { return sheet_sum.at({p[0] + 0.5, p[1] + 0.5, p[2] + 0.5}); };
        auto smooth = [&](const Int3& p) { return brick.minusCrossings(p) + shift(p) + sheetSum(p); };
        const Int3 m{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2};
        Int3 points[9];
        for (int c = 0; c < 8; ++c) points[c] = {c & 4 ? b[0] : a[0], c & 2 ? b[1] : a[1], c & 1 ? b[2] : a[2]};
        points[8] = m;
        brick.sample(points, 9);  // the corners and the middle the next lines read, in one walk
        double corner[8];
        for (int c = 0; c < 8; ++c) corner[c] = smooth(points[c]);
        // The trilinear interpolation of the corners, along z from each column's ends.
        double t[3][9];  // per axis, (p - a) / (b - a) at p = a .. b
        for (int d = 0; d < 3; ++d)
            for (int n = 0; n <= b[d] - a[d]; ++n) t[d][n] = b[d] > a[d] ? double(n) / (b[d] - a[d]) : 0.0;
        auto columnEnds = [&](int i, int j, double& bottom, double& upper) {
            const double x = t[0][i - a[0]], y = t[1][j - a[1]];
            const double w00 = (1 - x) * (1 - y), w01 = (1 - x) * y, w10 = x * (1 - y), w11 = x * y;
            bottom = corner[0] * w00 + corner[2] * w01 + corner[4] * w10 + corner[6] * w11;
            upper = corner[1] * w00 + corner[3] * w01 + corner[5] * w10 + corner[7] * w11;
        };
        double m_bottom, m_top;
        columnEnds(m[0], m[1], m_bottom, m_top);
        const double m_interpolated = m_bottom + (m_top - m_bottom) * t[2][m[2] - a[2]];
        if (std::fabs(smooth(m) - m_interpolated) <= kAgree) {  // false for NaN
            for (int i = a[0]; i <= b[0]; ++i)
                for (int j = a[1]; j <= b[1]; ++j) {
                    unsigned bits = pendingColumn(i, j, a, b);
                    if (bits == 0) continue;
                    double bottom, top_value;
                    columnEnds(i, j, bottom, top_value);
                    const double shifted = shift({i, j, a[2]});
                    // The sampled voxels from their samples; the others' sheet sums together.
                    int steps[9], count = 0;
                    double heights[9], sheet_sums[9];
                    for (; bits != 0; bits &= bits - 1) {
                        const int dz = __builtin_ctz(bits);
                        const Int3 p{i, j, a[2] + dz};
                        if (brick.sampled(p)) {
                            decide(p, brick.crossings(p) + brick.minusCrossings(p));
                            continue;
                        }
                        steps[count] = dz;
                        heights[count++] = p[2] + 0.5;
                    }
                    if (sheet_sum.size() > 0)
                        sheet_sum.atColumn(i + 0.5, j + 0.5, heights, count, sheet_sums);
                    else
                        std::fill(sheet_sums, sheet_sums + count, 0.0);  // at()'s sum of no sheets
                    for (int q = 0; q < count; ++q) {
                        const Int3 p{i, j, a[2] + steps[q]};
                        const double interpolated = bottom + (top_value - bottom) * t[2][steps[q]];
                        const double w = brick.crossings(p) - shifted + interpolated - sheet_sums[q];
                        if (!(std::fabs(w - 0.5) >= kMargin)) {  // NaN too
                            defer(p);
                            continue;
                        }
                        ++counters.interpolated_voxels;
                        decide(p, w);
                    }
                }
            return;
        }
        // Halve every side of two or more voxels; the halves share the middle plane.
        for (int part = 0; part < 8; ++part) {
            Int3 ca = a, cb = b;
            bool skip = false;
            for (int d = 0; d < 3; ++d) {
                const bool upper = (part >> d) & 1;
                if (b[d] - a[d] < 2)
                    skip = skip || upper;
                else
                    (upper ? ca : cb)[d] = m[d];
            }
            if (!skip) self(self, ca, cb);
        }
    };
    visit(visit, lo, top);
    brick.exactWindings(outright, outright_values);
    for (std::size_t n = 0; n < outright.size(); ++n) decide(outright[n], outright_values[n]);
}

}  // namespace hyvox::solid
