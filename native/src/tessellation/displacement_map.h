// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The displacement height image (section 3.3): loaded from an 8/16-bit PNG (grey, grey+alpha,
// RGB(A) or palette; colour images use Blender's texture intensity, the mean of R, G, B) or
// taken from a float array, laid out as the shaders sample it (GL_LINEAR, clamped at the
// edges; tests/native/support/surface_twin.h samples it the same way on the CPU).
#include <string>
#include <vector>

#include "hyvox/options.h"

namespace hyvox::tessellation {

// Reads a PNG into 0..1 values, row 0 = the file's top row. Throws InvalidInput.
HeightImage readPngHeight(const std::string& path);

class DisplacementMap {
public:
    DisplacementMap() = default;
    // From the options: the PNG path if given, else the in-memory pixels; empty() when neither.
    // Throws InvalidInput for an unreadable file or a pixel array of the wrong size / NaNs.
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
