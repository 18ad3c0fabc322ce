// SPDX-License-Identifier: GPL-3.0-or-later
#include "tessellation/displacement_map.h"

#include <algorithm>
#include <cmath>

#include "hyvox/errors.h"

namespace hyvox::tessellation {

DisplacementMap::DisplacementMap(const HeightImage& image) : width_(image.width), height_(image.height) {
    if (image.width < 1 || image.height < 1 || image.values.size() != std::size_t(image.width) * image.height)
        throw InvalidInput("displacement pixels: expected width × height values, got " +
                           std::to_string(image.values.size()) + " for " + std::to_string(image.width) + "×" +
                           std::to_string(image.height));
    rows_.resize(image.values.size());
    for (int y = 0; y < height_; ++y)
        std::copy_n(image.values.begin() + std::ptrdiff_t(y) * width_, width_,
                    rows_.begin() + std::ptrdiff_t(height_ - 1 - y) * width_);
    for (float v : rows_)
        if (!std::isfinite(v)) throw InvalidInput("displacement pixels contain NaN or Inf");
    const auto [lo, hi] = std::minmax_element(rows_.begin(), rows_.end());
    min_ = *lo;
    max_ = *hi;
}

DisplacementMap DisplacementMap::fromOptions(const TessellationOptions& options) {
    if (!options.displacement_image.empty())
        throw BackendError("the displacement image reached the tessellation backend unread (the dispatcher reads it)");
    if (!options.displacement_pixels.empty()) return DisplacementMap(options.displacement_pixels);
    return {};
}

}  // namespace hyvox::tessellation
