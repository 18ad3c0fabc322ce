// SPDX-License-Identifier: GPL-3.0-or-later
#include "hybrid/cutoff_search.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

namespace hyvox::hybrid {

CutoffSearch searchCutoff(const std::function<double(double)>& time_at, double largest_area, int evaluations) {
    // The paper's Fig. 13/14: time over cutoff is a noisy staircase with one broad valley at a
    // few voxel units²; searching the logarithm spends the runs where the valley usually is.
    double lo = std::log2(0.25), hi = std::log2(std::max(1.0, largest_area) * 1.01);
    constexpr double kInvPhi = 0.6180339887498949;
    double a = hi - kInvPhi * (hi - lo), b = lo + kInvPhi * (hi - lo);
    double fa = time_at(std::exp2(a)), fb = time_at(std::exp2(b));
    CutoffSearch out;
    out.evaluations = 2;
    while (out.evaluations < std::max(3, evaluations)) {
        if (fa <= fb) {
            hi = b;
            b = a;
            fb = fa;
            a = hi - kInvPhi * (hi - lo);
            fa = time_at(std::exp2(a));
        } else {
            lo = a;
            a = b;
            fa = fb;
            b = lo + kInvPhi * (hi - lo);
            fb = time_at(std::exp2(b));
        }
        ++out.evaluations;
    }
    out.cutoff = std::exp2(fa <= fb ? a : b);
    return out;
}

CutoffSearch cachedCutoff(const std::string& key, const std::function<CutoffSearch()>& search) {
    static std::mutex mutex;
    static std::map<std::string, double> cache;
    {
        std::lock_guard<std::mutex> lock(mutex);
        const auto found = cache.find(key);
        if (found != cache.end()) return {found->second, 0, true};
    }
    CutoffSearch result = search();  // unlocked: the GL worker serializes the runs anyway
    std::lock_guard<std::mutex> lock(mutex);
    cache[key] = result.cutoff;
    return result;
}

}  // namespace hyvox::hybrid
