// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A colour image sampled at a mesh's UVs (attribute voxels): linear texels, row 0 = the
// image's top row (as in a PNG file), so v = 0 (Blender's UV convention) is the bottom row.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "hyvox/options.h"

namespace hyvox {

struct Texture {
    // Largest image accepted (texels): 8192² RGBA floats are 1 GiB.
    static constexpr std::uint64_t kMaxTexels = std::uint64_t(8192) * 8192;

    int width = 0;
    int height = 0;
    int channels = 0;          // 3 (RGB) or 4 (RGBA; alpha linear)
    std::vector<float> texels;  // width * height * channels, linear

    // Bilinear between texel centres ((x + 0.5) / width), repeat wrap; RGBA (alpha 1 for RGB).
    std::array<float, 4> sample(double u, double v) const;
};

// sRGB-encoded 0..1 to linear (IEC 61966-2-1).
double srgbToLinear(double encoded);

// From 8-bit (sRGB-encoded), 16-bit (sRGB-encoded) or float (linear) pixels, rows top first;
// throws InvalidInput for a size of zero, above kMaxTexels, channels other than 3 or 4, or
// non-finite values.
Texture textureFromBytes(const std::uint8_t* pixels, int width, int height, int channels);
Texture textureFromWords(const std::uint16_t* pixels, int width, int height, int channels);
Texture textureFromLinear(const float* pixels, int width, int height, int channels);

// Reads an 8- or 16-bit PNG (grey, grey+alpha, RGB, RGBA, palette: as RGB or RGBA), decoding
// sRGB to linear. Throws InvalidInput naming the file when it is missing, not a PNG, damaged
// or larger than kMaxTexels.
Texture readPngTexture(const std::string& path);

// Reads an 8- or 16-bit PNG as a displacement height image (hyvox/options.h): values 0..1,
// row 0 = the file's top row; a colour image's height is the mean of its R, G, B (Blender's
// texture intensity), an 8-bit file's values as stored (no gamma, as Blender's non-colour
// data). The same limits and errors as readPngTexture.
HeightImage readPngHeight(const std::string& path);

// One decoded image per material for MeshView::material_textures: `paths` has one entry per
// material, "" for none (Mesh::material_textures). Each file is read once.
struct MaterialTextures {
    std::vector<Texture> images;
    std::vector<const Texture*> of_material;  // null where the material has none
};
MaterialTextures readMaterialTextures(const std::vector<std::string>& paths);

}  // namespace hyvox
