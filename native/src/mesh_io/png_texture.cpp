// SPDX-License-Identifier: GPL-3.0-or-later
// The images hyvox reads, readPngTexture and readPngHeight (hyvox/texture.h), with libpng's
// simplified API, which expands grey, palette and low bit depths for us; one opening and one
// texel limit for both.
#include <png.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>

#include "hyvox/errors.h"
#include "hyvox/texture.h"

namespace hyvox {

namespace {

// A PNG file opened and its header read, checked against the one texel limit of every image
// hyvox reads (colour textures and displacement heights) before any pixel is allocated.
struct PngFile {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file{nullptr, &std::fclose};
    png_image image{};

    PngFile(const std::string& path, const char* what) {
        file.reset(std::fopen(path.c_str(), "rb"));
        if (!file) throw InvalidInput(std::string("cannot open ") + what + " '" + path + "'");
        image.version = PNG_IMAGE_VERSION;
        if (!png_image_begin_read_from_stdio(&image, file.get()))
            throw InvalidInput(std::string(what) + " '" + path + "' is not a readable PNG: " + image.message);
        if (std::uint64_t(image.width) * image.height > Texture::kMaxTexels) {
            png_image_free(&image);
            throw InvalidInput(std::string(what) + " '" + path + "' has " + std::to_string(image.width) + "x" +
                               std::to_string(image.height) + " texels, more than the limit of 8192x8192");
        }
    }
    PngFile(const PngFile&) = delete;
    PngFile& operator=(const PngFile&) = delete;
};

}  // namespace

Texture readPngTexture(const std::string& path) {
    PngFile png(path, "texture");
    png_image& image = png.image;
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
                    pixels[p + c] = pixels[p + 3]
                        ? std::uint16_t(std::min<std::uint32_t>(
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

HeightImage readPngHeight(const std::string& path) {
    PngFile png(path, "displacement image");
    png_image& image = png.image;
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
    const bool ok =
        sixteen ? decode(std::vector<png_uint_16>(count), 65535.0) : decode(std::vector<png_byte>(count), 255.0);
    if (!ok) throw InvalidInput("displacement image '" + path + "' could not be decoded: " + image.message);
    return out;
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
