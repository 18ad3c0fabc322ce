// SPDX-License-Identifier: GPL-3.0-or-later
// Eq. 3 of the point-tessellated voxelization paper: the γ ↔ bias fit (hyvox/accuracy.h).
#include <cmath>

#include "hyvox/accuracy.h"
#include "hyvox/errors.h"

namespace hyvox {

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
