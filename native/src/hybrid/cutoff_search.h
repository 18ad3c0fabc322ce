// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The hybrid method's automatic cutoff (section 3.4.1 suggests a bracketing search; the
// paper never did one): golden-section search on log2(cutoff) over a few timed runs, the
// GPU time of pass 1 + pass 2 as the objective. Results are cached per mesh fingerprint,
// grid, mode and device for the process lifetime.
#include <cstdint>
#include <functional>
#include <string>

namespace hyvox::hybrid {

struct CutoffSearch {
    double cutoff = 0;
    int evaluations = 0;
    bool cached = false;
};

// time_at(cutoff) runs the hybrid passes once and returns milliseconds. Searches
// [0.25, max(1, largest_area)] voxel units² with `evaluations` runs (at least 3).
CutoffSearch searchCutoff(const std::function<double(double)>& time_at, double largest_area, int evaluations = 7);

// Cache keyed by any string the caller builds (mesh fingerprint, dims, mode, device).
CutoffSearch cachedCutoff(const std::string& key, const std::function<CutoffSearch()>& search);

}  // namespace hyvox::hybrid
