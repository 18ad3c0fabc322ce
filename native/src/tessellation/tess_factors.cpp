// SPDX-License-Identifier: GPL-3.0-or-later
#include "tessellation/tess_factors.h"

#include <algorithm>
#include <cmath>

namespace hyvox::tessellation {

double edgeFactor(const Vec3f& a, const Vec3f& b, double gamma) {
    double squared = 0;
    for (int axis = 0; axis < 3; ++axis)
        squared += (double(a[axis]) - double(b[axis])) * (double(a[axis]) - double(b[axis]));
    return gamma * std::sqrt(squared);
}

double PatchFactors::largest() const { return std::max({outer[0], outer[1], outer[2], inner}); }

PatchFactors patchFactors(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2, double gamma) {
    PatchFactors f;
    f.outer = {edgeFactor(p1, p2, gamma), edgeFactor(p2, p0, gamma), edgeFactor(p0, p1, gamma)};
    f.inner = (f.outer[0] + f.outer[1] + f.outer[2]) / 3.0;
    return f;
}

int presplitPieces(const PatchFactors& factors, int max_level) {
    // Uniform n-splitting divides every edge (and the mean) by n.
    const double needed = std::ceil(factors.largest() / double(max_level));
    return needed <= 1.0 ? 1 : int(std::min(needed, 65535.0));
}

}  // namespace hyvox::tessellation
