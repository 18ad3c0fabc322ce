// SPDX-License-Identifier: GPL-3.0-or-later
// validate(): one pass over the vertices and one over the triangles, each cut into chunks
// that TBB checks in parallel (in the caller's arena). The pass over the triangles also sums
// what the memory estimate needs of them (TriangleSums), so that it need not read them again. A chunk stops at its first problem;
// the problem of the lowest chunk is reported, so the message names the same first bad
// vertex or triangle as a serial pass would.
#include "hyvox/mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <tuple>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/triangle_normal.h"
#include "hyvox/errors.h"
#include "hyvox/zero_page_allocator.h"

namespace hyvox {
namespace {

// Zero area: the normal of the corners in double is exactly zero. Double products of
// float inputs are exact enough that "exactly zero" is meaningful, and every backend skips the
// same triangles. The normal is the one every double method takes (from the two shortest
// edges, core/triangle_normal.h), so the rule does not depend on which corner comes first:
// a needle 1e-37 wide beside edges of 1e33 was zero from one corner's two edges and not
// from another's.
//
// Most triangles are far from zero area: the cross product of the edges from corner a decides
// them. Each way of computing a component (these edges or the two shortest, each at most
// twice as long per coordinate) errs by under 40 * 2^-53 * L^2, L the largest coordinate of
// e0 and e1; a component above 2^-40 * L^2 here therefore has a true value, and a value in the
// stable normal, far from zero. L^2 is bounded by the sum of the squares of the six
// coordinates (a few multiplications, where the largest of six takes a chain of comparisons):
// the bound is at most 6 L^2, and a larger bound only sends more triangles to the stable
// normal.
struct CornerCross {
    double n[3];        // (b - a) x (c - a)
    double square_sum;  // |b - a|^2 + |c - a|^2, at least L^2
};

CornerCross crossFromA(const float* a, const float* b, const float* c) {
    const double e0[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
    const double e1[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
    return {{e0[1] * e1[2] - e0[2] * e1[1], e0[2] * e1[0] - e0[0] * e1[2], e0[0] * e1[1] - e0[1] * e1[0]},
            (e0[0] * e0[0] + e0[1] * e0[1] + e0[2] * e0[2]) + (e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2])};
}

bool isZeroArea(const float* a, const float* b, const float* c, const CornerCross& x) {
    const double surely_not_zero = 0x1p-40 * x.square_sum;
    if (std::fabs(x.n[0]) > surely_not_zero || std::fabs(x.n[1]) > surely_not_zero ||
        std::fabs(x.n[2]) > surely_not_zero)
        return false;
    const auto corner = [](const float* p) { return Corner3{double(p[0]), double(p[1]), double(p[2])}; };
    const Corner3 stable = stableTriangleNormal(corner(a), corner(b), corner(c));
    return stable[0] == 0.0 && stable[1] == 0.0 && stable[2] == 0.0;
}

constexpr std::size_t kChunk = kInterruptCheckTriangles;
constexpr std::size_t kPrefetchAhead = 8;

std::size_t chunkCount(std::size_t n) { return (n + kChunk - 1) / kChunk; }

// The first problem each chunk found (empty: none); thrown for the lowest chunk.
void throwFirstProblem(const std::vector<std::string>& problems) {
    for (const std::string& problem : problems)
        if (!problem.empty()) throw InvalidInput(problem);
}

// A coordinate is usable when its magnitude is below this: NaN, Inf and the largest floats
// are not. Blender stores an infinite coordinate as the largest float (3.4028235e38), and a
// grid over such a vertex is nonsense (a voxel of 1e36 units), so those count as Inf.
constexpr float kNotACoordinate = 3.4e38f;

bool usableCoordinate(float x) { return std::fabs(x) < kNotACoordinate; }  // false for NaN

std::string coordinateText(float x) {
    if (std::isnan(x)) return "NaN";  // as the messages and the docs spell it ("%g" gives "nan")
    if (std::isinf(x)) return x > 0 ? "Inf" : "-Inf";
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", double(x));
    return text;
}

void checkVerticesFinite(const MeshView& mesh) {
    std::vector<std::string> problems(chunkCount(mesh.vertex_count));
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, problems.size(), 1), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t chunk = r.begin(); chunk != r.end(); ++chunk) {
                const std::size_t end = std::min(mesh.vertex_count, (chunk + 1) * kChunk);
                // The cheap test over the whole chunk first; the per-vertex search runs only on
                // chunks where it fails.
                bool all_usable = true;
                for (std::size_t i = 3 * chunk * kChunk; i < 3 * end; ++i)
                    all_usable &= usableCoordinate(mesh.positions[i]);
                if (all_usable) continue;
                for (std::size_t v = chunk * kChunk; v < end && problems[chunk].empty(); ++v)
                    for (int a = 0; a < 3; ++a)
                        if (!usableCoordinate(mesh.positions[3 * v + a])) {
                            const float x = mesh.positions[3 * v + a];
                            problems[chunk] = "vertex " + std::to_string(v) + " has a non-finite coordinate (" +
                                coordinateText(x) +
                                (std::isfinite(x) ? ", the largest float: Inf as Blender stores it)" : ")");
                            break;
                        }
            }
        });
    throwFirstProblem(problems);
}

// One chunk of triangles: its usable indices written from `usable` on (at most one per
// triangle), their bounds, their sums and its degenerate count, or the first problem in it.
// The volume is summed with its apex at the chunk's first usable corner, near every corner of
// the mesh, and moved to the mesh's bounds once they are known: an apex far from the mesh (the
// world's origin) would add large terms that cancel, and lose the volume's digits with them.
struct TriangleChunk {
    std::size_t usable_count = 0;
    std::size_t degenerate_count = 0;
    Bounds bounds;
    double crossed_twice = 0;               // Σ |n|₁
    double volume_six = 0;                  // Σ (a - apex) · n
    std::array<double, 3> normal{0, 0, 0};  // Σ n
    std::array<double, 3> apex{0, 0, 0};
    std::string problem;
};

void checkTriangles(const MeshView& mesh, std::size_t begin, std::size_t end, std::uint32_t* usable,
                    TriangleChunk& out) {
    // Bounds over floats (exact, as the doubles they widen to) and sums held in locals, each
    // sum taking one addition a triangle: the loop's chains of dependent operations stay short.
    const float inf = std::numeric_limits<float>::infinity();
    float lo[3] = {inf, inf, inf}, hi[3] = {-inf, -inf, -inf};
    double crossed_twice = 0, volume_six = 0, normal[3] = {0, 0, 0}, apex[3] = {0, 0, 0};
    std::size_t kept = 0, degenerate = 0;
    for (std::size_t t = begin; t < end; ++t) {
        // Vertices are spread over megabytes: those of a triangle a few ahead are requested now.
        if (t + kPrefetchAhead < end)
            for (int c = 0; c < 3; ++c) {
                const std::uint32_t ahead = mesh.triangles[3 * (t + kPrefetchAhead) + c];
                if (ahead < mesh.vertex_count) __builtin_prefetch(mesh.positions + 3 * std::size_t(ahead));
            }
        const std::uint32_t* idx = mesh.triangles + 3 * t;
        for (int c = 0; c < 3; ++c)
            if (idx[c] >= mesh.vertex_count) {
                out.problem = "triangle " + std::to_string(t) + " refers to vertex " + std::to_string(idx[c]) +
                    ", but the mesh has only " + std::to_string(mesh.vertex_count) + " vertices";
                return;
            }
        const float* a = mesh.positions + 3 * std::size_t(idx[0]);
        const float* b = mesh.positions + 3 * std::size_t(idx[1]);
        const float* c = mesh.positions + 3 * std::size_t(idx[2]);
        const CornerCross x = crossFromA(a, b, c);
        if (idx[0] == idx[1] || idx[1] == idx[2] || idx[0] == idx[2] || isZeroArea(a, b, c, x)) {
            ++degenerate;
            continue;
        }
        if (kept == 0)
            for (int axis = 0; axis < 3; ++axis) apex[axis] = a[axis];
        usable[kept++] = std::uint32_t(t);
        crossed_twice += std::fabs(x.n[0]) + std::fabs(x.n[1]) + std::fabs(x.n[2]);
        volume_six +=
            (double(a[0]) - apex[0]) * x.n[0] + (double(a[1]) - apex[1]) * x.n[1] + (double(a[2]) - apex[2]) * x.n[2];
        for (int axis = 0; axis < 3; ++axis) {
            normal[axis] += x.n[axis];
            const float pa = a[axis], pb = b[axis], pc = c[axis];
            const float least = pb < pa ? pb : pa, most = pb > pa ? pb : pa;
            const float least3 = pc < least ? pc : least, most3 = pc > most ? pc : most;
            lo[axis] = least3 < lo[axis] ? least3 : lo[axis];
            hi[axis] = most3 > hi[axis] ? most3 : hi[axis];
        }
    }
    out.usable_count = kept;
    out.degenerate_count = degenerate;
    out.crossed_twice = crossed_twice;
    out.volume_six = volume_six;
    for (int axis = 0; axis < 3; ++axis) {
        out.normal[axis] = normal[axis];
        out.apex[axis] = apex[axis];
        out.bounds.min[axis] = lo[axis];
        out.bounds.max[axis] = hi[axis];
    }
}

// The chunks' sums as the mesh's (TriangleSums), the volume's apex moved to the bounds' min.
void sumChunks(const std::vector<TriangleChunk>& chunks, ValidatedMesh& out) {
    double crossed_twice = 0, volume_six = 0;
    std::array<double, 3> normal{0, 0, 0};
    for (const TriangleChunk& chunk : chunks) {
        if (chunk.usable_count == 0) continue;
        crossed_twice += chunk.crossed_twice;
        volume_six += chunk.volume_six;
        for (int axis = 0; axis < 3; ++axis) {
            volume_six -= (out.bounds.min[axis] - chunk.apex[axis]) * chunk.normal[axis];
            normal[axis] += chunk.normal[axis];
        }
    }
    out.sums.crossed_area = crossed_twice / 2;
    out.sums.volume = volume_six / 6;
    for (int axis = 0; axis < 3; ++axis) out.sums.normal[axis] = normal[axis] / 6;
}

}  // namespace

ValidatedMesh validate(const MeshView& mesh, Interrupter* interrupter) {
    if (mesh.vertex_count == 0 || mesh.triangle_count == 0)
        throw InvalidInput("the mesh is empty (" + std::to_string(mesh.vertex_count) + " vertices, " +
                           std::to_string(mesh.triangle_count) + " triangles)");
    if (!mesh.positions || !mesh.triangles) throw InvalidInput("the mesh has no vertex or triangle data");
    if (mesh.vertex_count > std::numeric_limits<std::uint32_t>::max())
        throw InvalidInput("too many vertices for 32-bit indices");

    checkVerticesFinite(mesh);
    for (const auto& [values, width, name] : {std::tuple{mesh.uvs, 2, "UV"}, std::tuple{mesh.normals, 3, "normal"}})
        if (values)
            for (std::size_t i = 0; i < mesh.vertex_count * width; ++i)
                if (!std::isfinite(values[i]))
                    throw InvalidInput("vertex " + std::to_string(i / width) + " has a non-finite " + name);

    ValidatedMesh out;
    out.view = mesh;
    // Each chunk writes its usable indices at its own first triangle; the gaps left by
    // degenerate triangles are closed after (no moves at all when none is degenerate).
    out.usable.reserve(mesh.triangle_count);
    adviseHugePages(out.usable.data(), mesh.triangle_count * sizeof(std::uint32_t));
    out.usable.resize(mesh.triangle_count);
    std::vector<TriangleChunk> chunks(chunkCount(mesh.triangle_count));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks.size(), 1),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t chunk = r.begin(); chunk != r.end(); ++chunk) {
                              throwIfInterrupted(interrupter);
                              const std::size_t begin = chunk * kChunk;
                              checkTriangles(mesh, begin, std::min(mesh.triangle_count, begin + kChunk),
                                             out.usable.data() + begin, chunks[chunk]);
                          }
                      });
    for (const TriangleChunk& chunk : chunks)
        if (!chunk.problem.empty()) throw InvalidInput(chunk.problem);

    const double inf = std::numeric_limits<double>::infinity();
    out.bounds.min = {inf, inf, inf};
    out.bounds.max = {-inf, -inf, -inf};
    std::size_t kept = 0;
    for (std::size_t c = 0; c < chunks.size(); ++c) {
        const TriangleChunk& chunk = chunks[c];
        if (kept != c * kChunk && chunk.usable_count > 0)
            std::memmove(out.usable.data() + kept, out.usable.data() + c * kChunk,
                         chunk.usable_count * sizeof(std::uint32_t));
        kept += chunk.usable_count;
        out.degenerate_count += chunk.degenerate_count;
        if (chunk.usable_count == 0) continue;
        for (int axis = 0; axis < 3; ++axis) {
            out.bounds.min[axis] = std::min(out.bounds.min[axis], chunk.bounds.min[axis]);
            out.bounds.max[axis] = std::max(out.bounds.max[axis], chunk.bounds.max[axis]);
        }
    }
    out.usable.resize(kept);
    if (out.usable.empty())
        throw InvalidInput("all " + std::to_string(mesh.triangle_count) +
                           " triangles are degenerate (zero area); nothing to voxelize");
    sumChunks(chunks, out);
    return out;
}

}  // namespace hyvox
