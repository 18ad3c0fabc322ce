// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/texture.h"

#include <cmath>

#include "hyvox/errors.h"

namespace hyvox {
namespace {

void checkSize(int width, int height, int channels) {
    if (width < 1 || height < 1)
        throw InvalidInput("a texture needs at least one texel, got " + std::to_string(width) + "x" +
                           std::to_string(height));
    if (channels != 3 && channels != 4)
        throw InvalidInput("a texture has 3 (RGB) or 4 (RGBA) channels, got " + std::to_string(channels));
    if (std::uint64_t(width) * std::uint64_t(height) > Texture::kMaxTexels)
        throw InvalidInput("a texture of " + std::to_string(width) + "x" + std::to_string(height) +
                           " texels is larger than the limit of 8192x8192");
}

// Encoded channels (0..1) to a texture: colour decoded from sRGB, alpha kept.
template <typename Pixel>
Texture decoded(const Pixel* pixels, int width, int height, int channels, double maximum) {
    checkSize(width, height, channels);
    Texture out{width, height, channels, {}};
    const std::size_t count = std::size_t(width) * std::size_t(height) * std::size_t(channels);
    out.texels.resize(count);
    // 256 or 65536 levels: one table instead of a pow per texel.
    std::vector<float> table(std::size_t(maximum) + 1);
    for (std::size_t level = 0; level < table.size(); ++level)
        table[level] = float(srgbToLinear(double(level) / maximum));
    // Texel by texel, channel by channel (no n % channels per value).
    const std::size_t stride = std::size_t(channels);
    for (std::size_t texel = 0; texel < count; texel += stride) {
        for (std::size_t c = 0; c < 3; ++c) out.texels[texel + c] = table[pixels[texel + c]];
        if (stride == 4) out.texels[texel + 3] = float(double(pixels[texel + 3]) / maximum);
    }
    return out;
}

}  // namespace

double srgbToLinear(double encoded) {
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

Texture textureFromBytes(const std::uint8_t* pixels, int width, int height, int channels) {
    return decoded(pixels, width, height, channels, 255.0);
}

Texture textureFromWords(const std::uint16_t* pixels, int width, int height, int channels) {
    return decoded(pixels, width, height, channels, 65535.0);
}

Texture textureFromLinear(const float* pixels, int width, int height, int channels) {
    checkSize(width, height, channels);
    Texture out{width, height, channels, {}};
    out.texels.assign(pixels, pixels + std::size_t(width) * std::size_t(height) * std::size_t(channels));
    for (float value : out.texels)
        if (!std::isfinite(value)) throw InvalidInput("texture pixels contain NaN or Inf");
    return out;
}

std::array<float, 4> Texture::sample(double u, double v) const {
    const double x = u * width - 0.5, y = (1.0 - v) * height - 0.5;
    const double x0 = std::floor(x), y0 = std::floor(y);
    const double fx = x - x0, fy = y - y0;
    // Repeat wrap; the floor is finite (UVs are validated finite) but may be far outside.
    auto wrap = [](double index, int size) {
        if (index >= 0 && index < size) return int(index);  // inside: what fmod would give, without the call
        const double r = std::fmod(index, double(size));
        return int(r < 0 ? r + size : r);
    };
    const int xa = wrap(x0, width), ya = wrap(y0, height);
    const int xb = xa + 1 == width ? 0 : xa + 1, yb = ya + 1 == height ? 0 : ya + 1;  // no integer division
    auto texel = [&](int tx, int ty, int c) {
        return double(
            texels[(std::size_t(ty) * std::size_t(width) + std::size_t(tx)) * std::size_t(channels) + std::size_t(c)]);
    };
    std::array<float, 4> out{0, 0, 0, 1};
    for (int c = 0; c < channels; ++c) {
        const double top = texel(xa, ya, c) * (1 - fx) + texel(xb, ya, c) * fx;
        const double bottom = texel(xa, yb, c) * (1 - fx) + texel(xb, yb, c) * fx;
        out[std::size_t(c)] = float(top * (1 - fy) + bottom * fy);
    }
    return out;
}

}  // namespace hyvox
