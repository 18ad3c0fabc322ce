// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/accuracy.h"

#include <cmath>

#include "hyvox/errors.h"

namespace hyvox {
namespace {

void requireSameDims(const BitGrid& a, const BitGrid& b) {
    if (a.dims() != b.dims()) throw InvalidInput("accuracy: the result and the reference have different dims");
}

}  // namespace

AccuracyReport compareToReference(const BitGrid& result, const BitGrid& reference) {
    requireSameDims(result, reference);
    AccuracyReport report;
    const std::uint64_t* r = result.data();
    const std::uint64_t* g = reference.data();
    for (std::size_t w = 0; w < result.wordCount(); ++w) {
        report.reference_voxels += std::uint64_t(__builtin_popcountll(g[w]));
        report.missed_voxels += std::uint64_t(__builtin_popcountll(g[w] & ~r[w]));
        report.false_voxels += std::uint64_t(__builtin_popcountll(r[w] & ~g[w]));
    }
    report.bias = report.reference_voxels ? double(report.missed_voxels) / double(report.reference_voxels) : 0.0;
    return report;
}

std::vector<std::array<std::int32_t, 3>> falseVoxels(const BitGrid& result, const BitGrid& reference) {
    requireSameDims(result, reference);
    BitGrid extra(result.dims());
    for (std::size_t w = 0; w < result.wordCount(); ++w) extra.data()[w] = result.data()[w] & ~reference.data()[w];
    return extra.coords();
}

WatertightReport rayMarchWatertightness(const BitGrid& result, const BitGrid& conservative, const BitGrid& thin) {
    requireSameDims(result, conservative);
    requireSameDims(result, thin);
    const auto& dims = result.dims();
    WatertightReport report;
    for (int axis = 0; axis < 3; ++axis) {
        const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
        const int length = dims[axis];
        for (int direction : {+1, -1})
            for (int u = 0; u < dims[a1]; ++u)
                for (int v = 0; v < dims[a2]; ++v) {
                    // Voxel `step` along the ray in grid `g`.
                    auto at = [&](const BitGrid& g, int step) {
                        std::array<int, 3> c{};
                        c[axis] = direction > 0 ? step : length - 1 - step;
                        c[a1] = u;
                        c[a2] = v;
                        return g.test(c[0], c[1], c[2]);
                    };
                    int crossing = 0;
                    while (crossing < length && !at(thin, crossing)) ++crossing;
                    bool pass = true;
                    if (crossing < length) {
                        int end = crossing;  // one past the conservative run around the crossing
                        while (end < length && at(conservative, end)) ++end;
                        int hit = 0;
                        while (hit <= end && hit < length && !at(result, hit)) ++hit;
                        pass = hit <= end && hit < length;
                    }
                    ++report.rays;
                    report.passed += pass ? 1 : 0;
                }
    }
    return report;
}

double GammaBiasFit::gammaFor(double bias) const { return -B * std::log(A * bias); }
double GammaBiasFit::biasFor(double gamma) const { return std::exp(-gamma / B) / A; }

GammaBiasFit fitGammaBias(const std::vector<double>& gammas, const std::vector<double>& biases) {
    if (gammas.size() != biases.size()) throw InvalidInput("fitGammaBias: as many biases as gammas are needed");
    // γ = c0 + c1 · ln p with c1 = -B and c0 = -B · ln A.
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < gammas.size(); ++i) {
        if (!(biases[i] > 0)) continue;  // ln 0: a perfect sample says nothing about the slope
        const double x = std::log(biases[i]), y = gammas[i];
        n += 1;
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    const double denominator = n * sxx - sx * sx;
    if (n < 2 || !(std::abs(denominator) > 1e-300))
        throw InvalidInput("fitGammaBias: needs at least two samples with different biases > 0");
    const double c1 = (n * sxy - sx * sy) / denominator;
    const double c0 = (sy - c1 * sx) / n;
    GammaBiasFit fit;
    fit.B = -c1;
    fit.A = std::exp(c0 / c1);
    return fit;
}

}  // namespace hyvox
