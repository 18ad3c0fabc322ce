// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// A colour image sampled at a mesh's UVs (attribute voxels): linear texels, row 0 = the
/// image's top row (as in a PNG file), so v = 0 (Blender's UV convention) is the bottom row.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "hyvox/options.h"

namespace hyvox {

/// A decoded image: linear texels, rows top first.
struct Texture {
    /// Largest image accepted (texels): 8192² RGBA floats are 1 GiB.
    static constexpr std::uint64_t kMaxTexels = std::uint64_t(8192) * 8192;

    int width = 0;              ///< texels per row
    int height = 0;             ///< rows
    int channels = 0;           ///< 3 (RGB) or 4 (RGBA; alpha linear)
    std::vector<float> texels;  ///< width * height * channels, linear

    /// Bilinear between texel centres ((x + 0.5) / width), repeat wrap; RGBA (alpha 1 for RGB).
    /// Thread-safe (const).
    /// @param u 0..1 across a row (repeats outside)
    /// @param v 0..1 from the bottom row up (Blender's UV convention; repeats outside)
    std::array<float, 4> sample(double u, double v) const;
};

/// sRGB-encoded 0..1 to linear (IEC 61966-2-1).
double srgbToLinear(double encoded);

/// A texture from 8-bit (sRGB-encoded), 16-bit (sRGB-encoded) or float (linear) pixels.
/// @param pixels width * height * channels values, rows top first (copied)
/// @param width texels per row
/// @param height rows
/// @param channels 3 (RGB) or 4 (RGBA)
/// @throws InvalidInput a size of zero, above kMaxTexels, channels other than 3 or 4, or
///         non-finite values
///@{
Texture textureFromBytes(const std::uint8_t* pixels, int width, int height, int channels);
Texture textureFromWords(const std::uint16_t* pixels, int width, int height, int channels);
Texture textureFromLinear(const float* pixels, int width, int height, int channels);
///@}

/// Reads an 8- or 16-bit PNG (grey, grey+alpha, RGB, RGBA, palette: as RGB or RGBA), decoding
/// sRGB to linear. Reentrant.
/// @throws InvalidInput naming the file when it is missing, not a PNG, damaged or larger than
///         kMaxTexels
Texture readPngTexture(const std::string& path);

/// Reads an 8- or 16-bit PNG as a displacement height image (hyvox/options.h): values 0..1,
/// row 0 = the file's top row; a colour image's height is the mean of its R, G, B (Blender's
/// texture intensity), an 8-bit file's values as stored (no gamma, as Blender's non-colour
/// data). The same limits and errors as readPngTexture.
HeightImage readPngHeight(const std::string& path);

/// One decoded image per material, for MeshView::material_textures.
struct MaterialTextures {
    std::vector<Texture> images;              ///< each file once (of_material points into it)
    std::vector<const Texture*> of_material;  ///< null where the material has none
};
/// Reads the images of `paths`, one entry per material, "" for none (Mesh::material_textures);
/// each file is read once.
/// @throws InvalidInput as readPngTexture() does
MaterialTextures readMaterialTextures(const std::vector<std::string>& paths);

}  // namespace hyvox
