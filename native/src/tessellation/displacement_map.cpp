// SPDX-License-Identifier: GPL-3.0-or-later
#include "tessellation/displacement_map.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "hyvox/errors.h"

namespace hyvox::tessellation {

HeightImage readPngHeight(const std::string& path) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) throw InvalidInput("cannot open displacement image '" + path + "'");
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_stdio(&image, file.get()))
        throw InvalidInput("displacement image '" + path + "' is not a readable PNG: " + image.message);
    // libpng's simplified API converts any PNG to linear 16-bit grey; for colour images
    // it uses the sRGB luminance weights, so ask for RGB and average instead (Blender's
    // texture intensity). 16-bit output keeps a 16-bit file's precision; an 8-bit file's
    // sRGB-coded values are kept as stored (no gamma), like Blender's non-colour data.
    const bool colour = (image.format & PNG_FORMAT_FLAG_COLOR) != 0;
    const bool sixteen = (image.format & PNG_FORMAT_FLAG_LINEAR) != 0;  // 16-bit file
    image.format = (colour ? PNG_FORMAT_RGB : PNG_FORMAT_GRAY) | (sixteen ? PNG_FORMAT_FLAG_LINEAR : 0);
    const int channels = colour ? 3 : 1;
    const std::size_t count = std::size_t(image.width) * image.height * channels;
    HeightImage out;
    out.width = int(image.width);
    out.height = int(image.height);
    out.values.resize(std::size_t(image.width) * image.height);
    // Decode into `raw` (8- or 16-bit samples) and average each pixel's channels to 0..1.
    auto decode = [&](auto raw, double maximum) {
        if (!png_image_finish_read(&image, nullptr, raw.data(), 0, nullptr)) return false;
        for (std::size_t p = 0; p < out.values.size(); ++p) {
            double sum = 0;
            for (int c = 0; c < channels; ++c) sum += raw[p * channels + c];
            out.values[p] = float(sum / (channels * maximum));
        }
        return true;
    };
    const bool ok = sixteen ? decode(std::vector<png_uint_16>(count), 65535.0) : decode(std::vector<png_byte>(count), 255.0);
    if (!ok) throw InvalidInput("displacement image '" + path + "' could not be decoded: " + image.message);
    return out;
}

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
    if (!options.displacement_image.empty()) return DisplacementMap(readPngHeight(options.displacement_image));
    if (!options.displacement_pixels.empty()) return DisplacementMap(options.displacement_pixels);
    return {};
}

}  // namespace hyvox::tessellation
