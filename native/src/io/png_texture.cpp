// SPDX-License-Identifier: GPL-3.0-or-later
// readPngTexture (hyvox/texture.h) with libpng's simplified API, which expands grey, palette
// and low bit depths to RGB(A) for us.
#include <png.h>

#include <cstdio>
#include <memory>

#include "hyvox/errors.h"
#include "hyvox/texture.h"

namespace hyvox {

Texture readPngTexture(const std::string& path) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) throw InvalidInput("cannot open texture '" + path + "'");
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_stdio(&image, file.get()))
        throw InvalidInput("texture '" + path + "' is not a readable PNG: " + image.message);
    // Checked before the pixels are allocated.
    if (std::uint64_t(image.width) * image.height > Texture::kMaxTexels) {
        png_image_free(&image);
        throw InvalidInput("texture '" + path + "' has " + std::to_string(image.width) + "x" +
                           std::to_string(image.height) + " texels, more than the limit of 8192x8192");
    }
    const bool alpha = (image.format & PNG_FORMAT_FLAG_ALPHA) != 0;
    // 8-bit sRGB output: an 8-bit file's bytes as stored; a 16-bit file is reduced to 8 bits
    // by libpng (colour decoded through its gamma; precision past 8 bits is not kept).
    const int channels = alpha ? 4 : 3;
    image.format = alpha ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
    std::vector<std::uint8_t> pixels(std::size_t(image.width) * image.height * std::size_t(channels));
    if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr))
        throw InvalidInput("texture '" + path + "' could not be decoded: " + image.message);
    return textureFromBytes(pixels.data(), int(image.width), int(image.height), channels);
}

}  // namespace hyvox
