// SPDX-License-Identifier: GPL-3.0-or-later
// readPngTexture (hyvox/texture.h) with libpng's simplified API, which expands grey, palette
// and low bit depths to RGB(A) for us.
#include <png.h>

#include <algorithm>
#include <cstdio>
#include <map>
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
    const int channels = alpha ? 4 : 3;
    const std::size_t samples = std::size_t(image.width) * image.height * std::size_t(channels);
    if (image.format & PNG_FORMAT_FLAG_LINEAR) {
        // A 16-bit file: libpng's 16-bit output gives its samples as stored (it takes 16-bit
        // data for linear), with colour premultiplied by alpha, undone here. They are
        // decoded from sRGB like 8-bit ones (Blender's default for colour images).
        image.format = (alpha ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB) | PNG_FORMAT_FLAG_LINEAR;
        std::vector<std::uint16_t> pixels(samples);
        if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr))
            throw InvalidInput("texture '" + path + "' could not be decoded: " + image.message);
        if (alpha)
            for (std::size_t p = 0; p < samples; p += 4)
                for (std::size_t c = 0; c < 3; ++c)
                    pixels[p + c] = pixels[p + 3] ? std::uint16_t(std::min<std::uint32_t>(
                                                        65535u, (std::uint32_t(pixels[p + c]) * 65535u + pixels[p + 3] / 2) / pixels[p + 3]))
                                                  : 0;
        return textureFromWords(pixels.data(), int(image.width), int(image.height), channels);
    }
    image.format = alpha ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
    std::vector<std::uint8_t> pixels(samples);
    if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr))
        throw InvalidInput("texture '" + path + "' could not be decoded: " + image.message);
    return textureFromBytes(pixels.data(), int(image.width), int(image.height), channels);
}

MaterialTextures readMaterialTextures(const std::vector<std::string>& paths) {
    MaterialTextures out;
    std::map<std::string, std::size_t> image_of_path;
    std::vector<std::size_t> image_of_material(paths.size(), 0);
    for (std::size_t m = 0; m < paths.size(); ++m) {
        if (paths[m].empty()) continue;
        const auto [it, inserted] = image_of_path.emplace(paths[m], out.images.size());
        if (inserted) out.images.push_back(readPngTexture(paths[m]));
        image_of_material[m] = it->second;
    }
    // Pointers once the images no longer move.
    out.of_material.assign(paths.size(), nullptr);
    for (std::size_t m = 0; m < paths.size(); ++m)
        if (!paths[m].empty()) out.of_material[m] = &out.images[image_of_material[m]];
    return out;
}

}  // namespace hyvox
