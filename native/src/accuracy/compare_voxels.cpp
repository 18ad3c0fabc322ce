// SPDX-License-Identifier: GPL-3.0-or-later
// Bias and false voxels: the two voxel sets compared word by word.
#include "accuracy/same_dims.h"
#include "hyvox/accuracy.h"

namespace hyvox {

using accuracy::requireSameDims;

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

AccuracyReport compareToReference(const SparseGrid& result, const SparseGrid& reference) {
    return compareToReference(result.toBitGrid(), reference.toBitGrid());
}

std::vector<std::array<std::int32_t, 3>> falseVoxels(const SparseGrid& result, const SparseGrid& reference) {
    return falseVoxels(result.toBitGrid(), reference.toBitGrid());
}

}  // namespace hyvox
