// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The displacement height image (section 3.3), laid out as the shaders sample it (GL_LINEAR,
// clamped at the edges; tests/native/support/surface_twin.h samples it the same way on the
// CPU). Backends are given the image as data: the dispatcher reads a displacement_image file
// into displacement_pixels with io's PNG reader (hyvox::readPngHeight) before they run.
#include <string>
#include <vector>

#include "hyvox/options.h"

namespace hyvox::tessellation {

class DisplacementMap {
public:
    DisplacementMap() = default;
    // From the options' pixels; empty() when there are none. Throws InvalidInput for a pixel
    // array of the wrong size or with NaNs.
    static DisplacementMap fromOptions(const TessellationOptions& options);
    explicit DisplacementMap(const HeightImage& image);

    bool empty() const { return rows_.empty(); }
    int width() const { return width_; }
    int height() const { return height_; }
    // Rows bottom-up (v = 0 first), the order glTexImage2D wants for UV lookups.
    const std::vector<float>& bottomUpRows() const { return rows_; }
    float minValue() const { return min_; }
    float maxValue() const { return max_; }

private:
    int width_ = 0, height_ = 0;
    std::vector<float> rows_;
    float min_ = 0, max_ = 0;
};

}  // namespace hyvox::tessellation
