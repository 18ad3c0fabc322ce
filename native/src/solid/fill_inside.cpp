// SPDX-License-Identifier: GPL-3.0-or-later
#include "solid/fill_inside.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "hyvox/region.h"
#include "solid/edge_closure.h"
#include "solid/fast_winding.h"
#include "solid/gradient_bound.h"
#include "solid/ray_crossings.h"
#include "solid/sheet_winding.h"
#include "solid/smooth_winding.h"

namespace hyvox::solid {
namespace {

using Int3 = std::array<std::int32_t, 3>;

// Halving a box [lo, hi) of bricks or voxels: middle() cuts every side longer than 1 in two;
// octant n (bits for x, y, z from high to low) takes the upper half of side a when its bit is
// set, and is empty (octant() false) when that half is (a side of length 1 has no upper half).
Int3 middle(const Int3& lo, const Int3& hi) {
    Int3 mid;
    for (int a = 0; a < 3; ++a) mid[a] = hi[a] - lo[a] > 1 ? lo[a] + (hi[a] - lo[a]) / 2 : hi[a];
    return mid;
}
bool octant(const Int3& lo, const Int3& hi, const Int3& mid, int n, Int3& child_lo, Int3& child_hi) {
    bool empty = false;
    for (int a = 0; a < 3; ++a) {
        const bool upper = (n >> (2 - a)) & 1;
        child_lo[a] = upper ? mid[a] : lo[a];
        child_hi[a] = upper ? hi[a] : mid[a];
        empty = empty || child_lo[a] >= child_hi[a];
    }
    return !empty;
}

// The inside test of the chosen rule: a value compared with 0.5, and how fast it may change.
struct InsideField {
    // By ray crossings: their parity, or their signed sum (a closed mesh's exact winding number).
    const RayCrossings* rays = nullptr;
    bool parity = false;
    // Else by winding numbers: a closed mesh's from the tree (the winding rule asked), or an
    // open mesh's brick by brick.
    const FastWinding* winding = nullptr;
    const SmoothWinding* smooth = nullptr;
    const GradientBound* bound = nullptr;

    double value(int i, int j, int k) const {
        if (rays) {
            const int crossings = rays->at(i, j, k);
            return parity ? double(crossings & 1) : double(crossings);
        }
        if (smooth) return smooth->windingAt(i, j, k);
        return winding->at({i + 0.5, j + 0.5, k + 0.5});
    }
    double slope(const Box& box, double limit) const {
        if (rays) return bound->parityMayChange(box) ? HUGE_VAL : 0.0;
        return bound->windingSlope(box, limit);
    }
    // Whether a value found at one point could hold over the box (holds() below) if it lay
    // kLikelyMargin from 0.5, and then (`slope_bound`) the slope bound over the box. Asked before
    // the value is evaluated: near an open mesh's open edges the bound fails for most regions,
    // and one fast winding number costs far more than the bound. 0.6 is just above the margin
    // of an ordinary winding number (0 or 1, off by a few hundredths in the fast winding
    // numbers): a region whose value lies farther from 0.5 (inside nested or duplicated
    // shells: 2 or more, -1 or less) and whose bound lies between would have held, and is now
    // decided by its parts, as when holds() fails (more work, the same answer). A wider margin
    // evaluates many regions whose bound then fails (docs/why/solid.md).
    static constexpr double kLikelyMargin = 0.6;
    bool mayHold(const Box& box, double path, double& slope_bound) const {
        slope_bound = path <= 0 ? 0.0 : slope(box, kLikelyMargin / path);
        return slope_bound * path < kLikelyMargin;  // then the whole sum: the walk did not stop early
    }
    // holds() with the slope bound mayHold() found.
    static bool holdsWithin(double v, double slope_bound, double path) {
        const double margin = std::fabs(v - 0.5);
        return path <= 0 ? margin > 0 : margin > slope_bound * path;
    }
    // Whether a value `v` found at one point holds for every point reachable from it by a path
    // of length `path` inside `box` that never meets the surface.
    bool holds(double v, const Box& box, double path) const {
        return holdsWithin(v, path <= 0 ? 0.0 : slope(box, std::fabs(v - 0.5) / path), path);
    }
};

// A brick of the surface: its position and words (all set for a surface tile).
struct SurfaceBrick {
    Int3 at;
    const std::uint64_t* words;
};

struct Output {
    std::vector<SparseGrid::Leaf> leaves;
    std::vector<SparseGrid::Leaf> surface_leaves;  // the surface's voxels whose centre is inside
    std::vector<SparseGrid::TileRun> runs;
    std::vector<RayCrossings::Crossing> columns[64];  // a column of bricks' rays (decideColumn)
    std::vector<Vec3> centres;
    std::vector<double> windings;
    std::uint64_t uniform_regions = 0, component_decisions = 0, point_evaluations = 0;
    SmoothWinding::Counters smooth;
};

class InsideFill {
public:
    // `centres_on_surface`: also decide the surface voxels' centres (Output::surface_leaves).
    InsideFill(const GridSpec& grid, const InsideField& field, Interrupter* interrupter, bool centres_on_surface)
        : grid_(grid),
          bricks_(grid.bricks()),
          field_(field),
          interrupter_(interrupter),
          centres_on_surface_(centres_on_surface) {}

    // The bricks [lo, hi): the whole grid, or a region's box (whose surface bricks are all there).
    void run(std::vector<SurfaceBrick>& surface, const Int3& lo, const Int3& hi) {
        if (field_.rays) decideSurfaceByColumns(surface);
        node(lo, hi, surface.data(), surface.data() + surface.size());
    }
    tbb::enumerable_thread_specific<Output>& outputs() { return outputs_; }

private:
    // The voxels of bricks [lo, hi) inside the grid, as a closed box of voxel space.
    Box voxelBox(const Int3& lo, const Int3& hi) const {
        Box box;
        for (int a = 0; a < 3; ++a) {
            box.lo[a] = 8.0 * lo[a];
            box.hi[a] = std::min(8.0 * hi[a], double(grid_.dims[a]));
        }
        return box;
    }

    // The bits of a brick's voxels that lie inside the grid.
    void gridMask(const Int3& b, std::uint64_t mask[8]) const {
        const int nx = std::min(8, grid_.dims[0] - 8 * b[0]);
        const int ny = std::min(8, grid_.dims[1] - 8 * b[1]);
        const int nz = std::min(8, grid_.dims[2] - 8 * b[2]);
        std::uint64_t row = 0;
        for (int y = 0; y < ny; ++y)
            for (int z = 0; z < nz; ++z) row |= std::uint64_t(1) << (y * 8 + z);
        for (int x = 0; x < 8; ++x) mask[x] = x < nx ? row : 0;
    }

    void node(const Int3& lo, const Int3& hi, SurfaceBrick* first, SurfaceBrick* last) {
        throwIfInterrupted(interrupter_);
        const bool single = hi[0] - lo[0] == 1 && hi[1] - lo[1] == 1 && hi[2] - lo[2] == 1;
        if (first == last) {
            if (decideRegion(lo, hi)) return;
            if (single) {
                decideFreeBrick(lo);
                return;
            }
        } else if (single) {
            if (!field_.rays) decideBrick(lo, first->words);  // else decided by columns, before
            return;
        }
        // Split every side longer than one brick in half; the surface bricks follow.
        const Int3 mid = middle(lo, hi);
        struct Child {
            Int3 lo, hi;
            SurfaceBrick *first, *last;
        };
        std::vector<Child> children;
        std::vector<SurfaceBrick*> cuts{first, last};
        for (int a = 0; a < 3; ++a) {
            std::vector<SurfaceBrick*> finer;
            for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
                finer.push_back(cuts[c]);
                finer.push_back(
                    std::partition(cuts[c], cuts[c + 1], [&](const SurfaceBrick& b) { return b.at[a] < mid[a]; }));
            }
            finer.push_back(last);
            cuts = std::move(finer);
        }
        for (int n = 0; n < 8; ++n) {
            Child child{};
            if (!octant(lo, hi, mid, n, child.lo, child.hi)) continue;
            child.first = cuts[std::size_t(n)];
            child.last = cuts[std::size_t(n) + 1];
            children.push_back(child);
        }
        const std::uint64_t volume =
            std::uint64_t(hi[0] - lo[0]) * std::uint64_t(hi[1] - lo[1]) * std::uint64_t(hi[2] - lo[2]);
        if (last - first > 64 || volume > 512) {
            tbb::parallel_for(std::size_t(0), children.size(), [&](std::size_t c) {
                node(children[c].lo, children[c].hi, children[c].first, children[c].last);
            });
        } else {
            for (const Child& c : children) node(c.lo, c.hi, c.first, c.last);
        }
    }

    // A surface-free box of bricks decided by one test at its middle voxel, if the bound allows.
    bool decideRegion(const Int3& lo, const Int3& hi) {
        Output& out = outputs_.local();
        const Box box = voxelBox(lo, hi);
        Int3 centre;
        double path2 = 0;
        for (int a = 0; a < 3; ++a) {
            centre[a] = std::int32_t(std::floor(0.5 * (box.lo[a] + box.hi[a])));
            centre[a] = std::clamp(centre[a], std::int32_t(box.lo[a]), std::int32_t(box.hi[a]) - 1);
            const double c = centre[a] + 0.5;
            const double far = std::max(c - (box.lo[a] + 0.5), (box.hi[a] - 0.5) - c);
            path2 += far * far;
        }
        double slope_bound;
        if (!field_.mayHold(box, std::sqrt(path2), slope_bound)) return false;
        const double v = field_.value(centre[0], centre[1], centre[2]);
        ++out.point_evaluations;
        if (!InsideField::holdsWithin(v, slope_bound, std::sqrt(path2))) return false;
        ++out.uniform_regions;
        if (v >= 0.5) emitInside(lo, hi, out);
        return true;
    }

    void emitInside(const Int3& lo, const Int3& hi, Output& out) {
        // Whole bricks become tiles, runs along z; bricks cut by the grid's edge become leaves.
        const Int3 whole{grid_.dims[0] / 8, grid_.dims[1] / 8, grid_.dims[2] / 8};
        for (std::int32_t bx = lo[0]; bx < hi[0]; ++bx)
            for (std::int32_t by = lo[1]; by < hi[1]; ++by) {
                std::int32_t z_end = lo[2];
                if (bx < whole[0] && by < whole[1]) {
                    z_end = std::max(lo[2], std::min(hi[2], whole[2]));
                    if (z_end > lo[2])
                        out.runs.push_back({bricks_.index(bx, by, lo[2]), bricks_.index(bx, by, z_end - 1) + 1});
                }
                for (std::int32_t bz = z_end; bz < hi[2]; ++bz) {
                    SparseGrid::Leaf leaf{};
                    leaf.brick = bricks_.index(bx, by, bz);
                    gridMask({bx, by, bz}, leaf.words);
                    out.leaves.push_back(leaf);
                }
            }
    }

    // Sets the bits of voxels [lo, hi) (inside one brick) in `words`.
    static void setBox(const Int3& lo, const Int3& hi, std::uint64_t words[8]) {
        for (int i = lo[0]; i < hi[0]; ++i)
            for (int j = lo[1]; j < hi[1]; ++j)
                for (int k = lo[2]; k < hi[2]; ++k) words[i & 7] |= BitGrid::bitMask(j, k);
    }

    // A surface-free box of voxels inside one brick: decided by one test at its middle when the
    // bound allows, else split in halves, down to single voxels (which one test decides).
    void decideFreeBox(const Int3& lo, const Int3& hi, std::uint64_t words[8], Output& out) {
        Box box;
        Int3 centre;
        double path2 = 0;
        bool single = true;
        for (int a = 0; a < 3; ++a) {
            box.lo[a] = lo[a];
            box.hi[a] = hi[a];
            centre[a] = (lo[a] + hi[a] - 1) / 2;
            const double c = centre[a] + 0.5;
            const double far = std::max(c - (lo[a] + 0.5), (hi[a] - 0.5) - c);
            path2 += far * far;
            single = single && hi[a] - lo[a] == 1;
        }
        const double v = field_.value(centre[0], centre[1], centre[2]);
        ++out.point_evaluations;
        if (single || field_.holds(v, box, std::sqrt(path2))) {
            if (!single) ++out.uniform_regions;
            if (v >= 0.5) setBox(lo, hi, words);
            return;
        }
        const Int3 mid = middle(lo, hi);
        for (int n = 0; n < 8; ++n) {
            Int3 child_lo, child_hi;
            if (octant(lo, hi, mid, n, child_lo, child_hi)) decideFreeBox(child_lo, child_hi, words, out);
        }
    }

    // The in-grid voxels of brick b as a box.
    void brickVoxels(const Int3& b, Int3& lo, Int3& hi) const {
        for (int a = 0; a < 3; ++a) {
            lo[a] = 8 * b[a];
            hi[a] = std::min(8 * b[a] + 8, grid_.dims[a]);
        }
    }

    void decideFreeBrick(const Int3& b) {
        static const std::uint64_t kNone[8] = {};
        if (field_.smooth) return decideSmoothly(b, kNone);
        Output& out = outputs_.local();
        SparseGrid::Leaf leaf{};
        leaf.brick = bricks_.index(b[0], b[1], b[2]);
        Int3 lo, hi;
        brickVoxels(b, lo, hi);
        decideFreeBox(lo, hi, leaf.words, out);
        std::uint64_t any = 0;
        for (std::uint64_t w : leaf.words) any |= w;
        if (any) out.leaves.push_back(leaf);
    }

    // One brick voxel by voxel: each 6-connected part of its voxels outside the surface is
    // decided by one test when the bound over the part's longest path allows, else per voxel.
    // A brick of an open mesh by the smooth part of its winding number (solid/smooth_winding.h).
    void decideSmoothly(const Int3& b, const std::uint64_t surface[8]) {
        Output& out = outputs_.local();
        std::uint64_t wanted[8];
        gridMask(b, wanted);
        if (!centres_on_surface_)
            for (int x = 0; x < 8; ++x) wanted[x] &= ~surface[x];
        SparseGrid::Leaf leaf{};
        leaf.brick = bricks_.index(b[0], b[1], b[2]);
        Int3 lo, hi;
        brickVoxels(b, lo, hi);
        field_.smooth->decideBrick(lo, hi, wanted, leaf.words, out.smooth);
        SparseGrid::Leaf on_surface{};
        on_surface.brick = leaf.brick;
        for (int x = 0; x < 8; ++x) {
            on_surface.words[x] = leaf.words[x] & surface[x];
            leaf.words[x] &= ~surface[x];
        }
        keep(leaf, out.leaves);
        keep(on_surface, out.surface_leaves);
    }

    static void keep(const SparseGrid::Leaf& leaf, std::vector<SparseGrid::Leaf>& into) {
        std::uint64_t any = 0;
        for (std::uint64_t w : leaf.words) any |= w;
        if (any) into.push_back(leaf);
    }

    // The surface voxels of brick b whose centre is inside, by the winding numbers of all of
    // them in one walk of the tree (by rays: decideSurfaceByColumns).
    void surfaceCentres(const Int3& b, const std::uint64_t surface[8], Output& out) {
        Int3 lo, hi;
        brickVoxels(b, lo, hi);
        SparseGrid::Leaf leaf{};
        leaf.brick = bricks_.index(b[0], b[1], b[2]);
        std::uint64_t wanted[8];
        gridMask(b, wanted);
        for (int x = 0; x < 8; ++x) wanted[x] &= surface[x];
        auto forEachWanted = [&](auto&& f) {
            for (int x = 0; x < 8; ++x)
                for (std::uint64_t bits = wanted[x]; bits; bits &= bits - 1) {
                    const int n = __builtin_ctzll(bits);
                    f(x, n >> 3, n & 7);
                }
        };
        out.centres.clear();
        forEachWanted(
            [&](int x, int y, int z) { out.centres.push_back({lo[0] + x + 0.5, lo[1] + y + 0.5, lo[2] + z + 0.5}); });
        out.windings.resize(out.centres.size());
        field_.winding->atBox(out.centres.data(), out.centres.size(), out.windings.data());
        out.point_evaluations += out.centres.size();
        std::size_t n = 0;
        forEachWanted([&](int x, int y, int z) {
            if (out.windings[n++] >= 0.5) leaf.words[x] |= BitGrid::bitMask(y, z);
        });
        keep(leaf, out.surface_leaves);
    }

    // The surface bricks by ray crossings: every voxel from the crossings of its own ray below
    // its centre (exactly the value the rule gives it), the 64 rays of a column of bricks traced
    // once for all of that column's surface bricks (a ray's crossings do not depend on where it
    // starts; the rays of one brick would be traced again for every brick above it).
    void decideSurfaceByColumns(std::vector<SurfaceBrick>& surface) {
        std::sort(surface.begin(), surface.end(), [](const SurfaceBrick& a, const SurfaceBrick& b) {
            return a.at[0] != b.at[0] ? a.at[0] < b.at[0] : a.at[1] != b.at[1] ? a.at[1] < b.at[1] : a.at[2] < b.at[2];
        });
        std::vector<std::size_t> starts;  // of each column's run of bricks
        for (std::size_t n = 0; n < surface.size(); ++n)
            if (n == 0 || surface[n].at[0] != surface[n - 1].at[0] || surface[n].at[1] != surface[n - 1].at[1])
                starts.push_back(n);
        starts.push_back(surface.size());
        tbb::parallel_for(std::size_t(0), starts.size() - 1, [&](std::size_t c) {
            throwIfInterrupted(interrupter_);
            decideColumn(surface.data() + starts[c], surface.data() + starts[c + 1]);
        });
    }

    // The bricks [first, last) of one column of bricks, ascending in z.
    void decideColumn(const SurfaceBrick* first, const SurfaceBrick* last) {
        Output& out = outputs_.local();
        Int3 lo, hi;
        brickVoxels(first->at, lo, hi);
        const int ni = hi[0] - lo[0], nj = hi[1] - lo[1];
        field_.rays->columns(lo[0], lo[1], ni, nj, out.columns);
        for (int n = 0; n < ni * nj; ++n)
            std::sort(out.columns[n].begin(), out.columns[n].end(),
                      [](const RayCrossings::Crossing& a, const RayCrossings::Crossing& b) { return a.z < b.z; });
        // Per ray: the next crossing not yet passed, and the signed crossings below it.
        std::size_t next[64] = {};
        int below[64] = {};
        for (const SurfaceBrick* brick = first; brick != last; ++brick) {
            brickVoxels(brick->at, lo, hi);
            std::uint64_t inside[8] = {};
            for (int x = 0; x < ni; ++x)
                for (int y = 0; y < nj; ++y) {
                    const int ray = x * nj + y;
                    const std::vector<RayCrossings::Crossing>& crossings = out.columns[ray];
                    for (int z = 0; z < hi[2] - lo[2]; ++z) {
                        const double centre = lo[2] + z + 0.5;
                        for (; next[ray] < crossings.size() && crossings[next[ray]].z < centre; ++next[ray])
                            below[ray] += crossings[next[ray]].sign;
                        const double value = field_.parity ? double(below[ray] & 1) : double(below[ray]);
                        if (value >= 0.5) inside[x] |= BitGrid::bitMask(y, z);
                    }
                }
            SparseGrid::Leaf off_surface{}, on_surface{};
            off_surface.brick = on_surface.brick = bricks_.index(brick->at[0], brick->at[1], brick->at[2]);
            for (int x = 0; x < 8; ++x) {
                off_surface.words[x] = inside[x] & ~brick->words[x];
                on_surface.words[x] = inside[x] & brick->words[x];
            }
            keep(off_surface, out.leaves);
            if (centres_on_surface_) keep(on_surface, out.surface_leaves);
        }
    }

    void decideBrick(const Int3& b, const std::uint64_t surface[8]) {
        if (field_.smooth) return decideSmoothly(b, surface);
        Output& out = outputs_.local();
        if (centres_on_surface_) surfaceCentres(b, surface, out);
        std::uint64_t open[8];
        gridMask(b, open);
        for (int x = 0; x < 8; ++x) open[x] &= ~surface[x];
        const Box box = voxelBox(b, {b[0] + 1, b[1] + 1, b[2] + 1});
        SparseGrid::Leaf leaf{};
        leaf.brick = bricks_.index(b[0], b[1], b[2]);
        auto isOpen = [&](int n) { return (open[n >> 6] >> (n & 63)) & 1; };
        std::uint64_t seen[8] = {};
        int queue[512], depth[512];
        for (int start = 0; start < 512; ++start) {
            if (!isOpen(start) || ((seen[start >> 6] >> (start & 63)) & 1)) continue;
            // Breadth-first over the part: its voxels and the longest path from `start`.
            int head = 0, tail = 0, longest = 0;
            queue[tail++] = start;
            depth[start] = 0;
            seen[start >> 6] |= std::uint64_t(1) << (start & 63);
            while (head < tail) {
                const int n = queue[head++];
                const int x = n >> 6, y = (n >> 3) & 7, z = n & 7;
                longest = std::max(longest, depth[n]);
                const int steps[6][2] = {{x > 0, -64}, {x < 7, 64}, {y > 0, -8}, {y < 7, 8}, {z > 0, -1}, {z < 7, 1}};
                for (const auto& [ok, step] : steps) {
                    const int m = n + step;
                    if (!ok || !isOpen(m) || ((seen[m >> 6] >> (m & 63)) & 1)) continue;
                    seen[m >> 6] |= std::uint64_t(1) << (m & 63);
                    depth[m] = depth[n] + 1;
                    queue[tail++] = m;
                }
            }
            auto voxel = [&](int n) {
                return Int3{8 * b[0] + (n >> 6), 8 * b[1] + ((n >> 3) & 7), 8 * b[2] + (n & 7)};
            };
            const Int3 first = voxel(start);
            const double v = field_.value(first[0], first[1], first[2]);
            ++out.point_evaluations;
            if (field_.holds(v, box, double(longest))) {
                if (tail > 1) ++out.component_decisions;
                if (v >= 0.5)
                    for (int q = 0; q < tail; ++q) leaf.words[queue[q] >> 6] |= std::uint64_t(1) << (queue[q] & 63);
                continue;
            }
            // Undecided: the part's voxels in 4³ octants of the brick that hold no surface voxel
            // go box by box (straight paths stay in the octant); the rest voxel by voxel.
            std::uint64_t done[8] = {}, member[8] = {};
            for (int q = 0; q < tail; ++q) member[queue[q] >> 6] |= std::uint64_t(1) << (queue[q] & 63);
            for (int octant = 0; octant < 8; ++octant) {
                Int3 lo, hi;
                brickVoxels(b, lo, hi);
                bool free = true;
                for (int a = 0; a < 3; ++a) {
                    lo[a] = lo[a] + ((octant >> (2 - a)) & 1) * 4;
                    hi[a] = std::min(hi[a], lo[a] + 4);
                    free = free && lo[a] < hi[a];
                }
                for (int i = lo[0]; free && i < hi[0]; ++i)
                    for (int j = lo[1]; j < hi[1]; ++j)
                        for (int k = lo[2]; k < hi[2]; ++k) free = free && !(surface[i & 7] & BitGrid::bitMask(j, k));
                // A surface-free octant is 6-connected, so it lies wholly in one part: this one?
                if (!free || !(member[lo[0] & 7] & BitGrid::bitMask(lo[1], lo[2]))) continue;
                std::uint64_t words[8] = {};
                decideFreeBox(lo, hi, words, out);
                setBox(lo, hi, done);
                for (int x = 0; x < 8; ++x) leaf.words[x] |= words[x];
            }
            for (int q = 0; q < tail; ++q) {
                const int n = queue[q];
                if ((done[n >> 6] >> (n & 63)) & 1) continue;
                const double here = q == 0 ? v : field_.value(voxel(n)[0], voxel(n)[1], voxel(n)[2]);
                out.point_evaluations += q != 0;
                if (here >= 0.5) leaf.words[n >> 6] |= std::uint64_t(1) << (n & 63);
            }
        }
        std::uint64_t any = 0;
        for (std::uint64_t w : leaf.words) any |= w;
        if (any) out.leaves.push_back(leaf);
    }

    const GridSpec& grid_;
    BrickLayout bricks_;
    const InsideField& field_;
    Interrupter* interrupter_;
    bool centres_on_surface_;
    tbb::enumerable_thread_specific<Output> outputs_;
};

std::string edgeFinding(const EdgeClosure& c) {
    return std::to_string(c.boundary_edges) + " boundary, " + std::to_string(c.nonmanifold_edges) +
        " non-manifold and " + std::to_string(c.misoriented_edges) + " misoriented edges";
}

}  // namespace

// A point costs a term per open edge against a walk of the tree, and the sheets need no
// build (bench/results/open_sampling: both ways on the shared open meshes).
bool bySheets(std::size_t open_edges, std::size_t triangles) { return open_edges * 64 <= triangles; }

bool insideByRays(const EdgeClosure& closure, const VoxelizeOptions& options) {
    return options.solid.inside == InsideRule::Parity ||
        (options.solid.inside == InsideRule::Auto && closure.open_edges.empty());
}

SparseGrid fillInside(const ValidatedMesh& mesh, const GridSpec& grid, const SparseGrid& surface,
                      const VoxelizeOptions& options, Interrupter* interrupter, SolidStats& stats,
                      SparseGrid* surface_inside) {
    const int threads = options.threads > 0 ? options.threads : tbb::task_arena::automatic;
    tbb::task_arena arena(threads);
    const EdgeClosure closure = arena.execute([&] { return checkEdges(mesh, grid); });
    return fillInside(mesh, grid, surface, options, closure, interrupter, stats, surface_inside);
}

SparseGrid fillInside(const ValidatedMesh& mesh, const GridSpec& grid, const SparseGrid& surface,
                      const VoxelizeOptions& options, const EdgeClosure& closure, Interrupter* interrupter,
                      SolidStats& stats, SparseGrid* surface_inside, OpenSampling sampling) {
    // Everything here runs on the options' threads (the sorts and the trees' builds included).
    const int threads = options.threads > 0 ? options.threads : tbb::task_arena::automatic;
    tbb::task_arena arena(threads);
    stats.boundary_edges = closure.boundary_edges;
    stats.nonmanifold_edges = closure.nonmanifold_edges;
    stats.misoriented_edges = closure.misoriented_edges;
    // auto when every edge's uses cancel (a closed, consistently oriented mesh, or one whose
    // non-manifold edges are used as often each way): the winding number is an integer, the
    // signed sum of any ray's crossings, so the rays give it exactly and as fast as parity
    // (and, unlike parity, fill where shells overlap).
    const bool closed = closure.closedAndOriented();
    const bool balanced = closure.open_edges.empty();
    const InsideRule asked = options.solid.inside;
    const InsideRule rule = asked == InsideRule::Auto ? InsideRule::Winding : asked;
    const bool by_rays = insideByRays(closure, options);
    stats.inside_rule = toString(rule);
    stats.evaluation = by_rays ? "ray crossings" : "fast winding numbers";
    const std::string signed_count = ": the winding number is the signed count of ray crossings";
    if (asked != InsideRule::Auto)
        stats.reason = std::string("the inside option (") + edgeFinding(closure) + ")";
    else if (closed)
        stats.reason = "auto: closed and consistently oriented (every edge used twice, once each way)" + signed_count;
    else if (balanced)
        stats.reason = "auto: every edge used as often each way (" + edgeFinding(closure) + ")" + signed_count;
    else
        stats.reason = "auto: not closed and consistently oriented (" + edgeFinding(closure) + ")";

    const GradientBound bound(closure.open_edges);
    // An open mesh's winding numbers come from its rays (their integer part) and the smooth rest
    // (solid/smooth_winding.h), sampled from the open edges' sheets or from the fast winding tree.
    const bool open = !by_rays && !bound.empty();
    const bool by_sheets = open &&
        (sampling == OpenSampling::Rule ? bySheets(bound.edgeCount(), mesh.usable.size())
                                        : sampling == OpenSampling::Sheets);
    if (by_sheets) stats.evaluation = "sheets of the open edges";
    std::unique_ptr<FastWinding> winding;
    std::unique_ptr<RayCrossings> rays;
    // The fast winding tree and the rays are independent: built side by side.
    arena.execute([&] {
        tbb::parallel_invoke(
            [&] {
                if (!by_rays && !by_sheets)
                    winding = std::make_unique<FastWinding>(mesh, grid, options.solid.winding_beta);
            },
            [&] {
                if (by_rays || open) rays = std::make_unique<RayCrossings>(mesh, grid);
            });
    });
    std::unique_ptr<WindingLessCrossings> less;
    std::unique_ptr<SmoothWinding> smooth;
    if (open) {
        if (by_sheets)
            less = std::make_unique<SheetWinding>(mesh, grid, bound, options.solid.winding_beta);
        else
            less = std::make_unique<TreeLessCrossings>(*winding);
        smooth = std::make_unique<SmoothWinding>(*less, *rays, bound, grid.dims);
    }
    InsideField field;
    field.rays = by_rays ? rays.get() : nullptr;
    field.parity = rule == InsideRule::Parity;
    field.winding = winding.get();
    field.smooth = smooth.get();
    field.bound = &bound;

    // The surface's bricks, tiles included (every voxel of a tile is surface).
    static const std::uint64_t kAllSet[8] = {~0ull, ~0ull, ~0ull, ~0ull, ~0ull, ~0ull, ~0ull, ~0ull};
    std::vector<SurfaceBrick> bricks;
    bricks.reserve(surface.leafCount() + surface.tileCount());
    for (const SparseGrid::Leaf& leaf : surface.leaves())
        bricks.push_back({surface.bricks().at(leaf.brick), leaf.words});
    for (const SparseGrid::TileRun& run : surface.tileRuns())
        for (std::uint64_t b = run.begin; b < run.end; ++b) bricks.push_back({surface.bricks().at(b), kAllSet});

    // A region's inside is decided over its box alone: the surface outside it is not known here.
    const RegionBox box = regionBox(grid, options.region);
    InsideFill fill(grid, field, interrupter, surface_inside != nullptr);
    arena.execute([&] { fill.run(bricks, box.brickLo(), box.brickHi()); });

    SparseGrid inside(grid.dims);
    if (surface_inside) *surface_inside = SparseGrid(grid.dims);
    for (Output& out : fill.outputs()) {
        for (const SparseGrid::Leaf& leaf : out.leaves) inside.addLeaf(leaf);
        if (surface_inside)
            for (const SparseGrid::Leaf& leaf : out.surface_leaves) surface_inside->addLeaf(leaf);
        for (const SparseGrid::TileRun& run : out.runs) inside.addTileRun(run.begin, run.end);
        stats.uniform_regions += out.uniform_regions;
        stats.component_decisions += out.component_decisions;
        stats.point_evaluations += out.point_evaluations + out.smooth.point_evaluations;
        stats.interpolated_voxels += out.smooth.interpolated_voxels;
        out = Output{};
    }
    if (smooth) stats.point_evaluations += smooth->sampleEvaluations();
    inside.finish();
    if (surface_inside) surface_inside->finish();
    stats.inside_voxels = inside.count();
    return inside;
}

}  // namespace hyvox::solid
