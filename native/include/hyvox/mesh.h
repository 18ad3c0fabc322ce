// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// A non-owning view of a triangle mesh (float32 positions N×3, uint32 triangles M×3),
/// and the validated form every backend consumes.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hyvox/interrupter.h"

namespace hyvox {

/// Loops over every triangle ask their Interrupter this often (validate, binning).
inline constexpr std::size_t kInterruptCheckTriangles = 65536;

struct Texture;  // hyvox/texture.h

/// A triangle mesh as the caller holds it: pointers to its arrays, which must stay valid and
/// unchanged while a call that takes the view runs (hyvox copies none of them). Positions in
/// world units; every array is row-major, one row per vertex, triangle or corner.
struct MeshView {
    const float* positions = nullptr;          ///< vertex_count * 3 floats, world units
    std::size_t vertex_count = 0;              ///< rows of positions (and of per-vertex arrays)
    const std::uint32_t* triangles = nullptr;  ///< triangle_count * 3 vertex indices
    std::size_t triangle_count = 0;            ///< rows of triangles
    // Optional per-vertex attributes (the tessellation method's PN-triangles and
    // displacement use them); null = absent. Normals need not be unit length.
    const float* uvs = nullptr;      ///< vertex_count * 2 (Blender UV: v = 0 is the image's bottom row)
    const float* normals = nullptr;  ///< vertex_count * 3; absent: area-weighted vertex normals

    // Surface attributes for attribute voxels (docs/design.md, "Attributes"); null = absent.
    // Colour comes from the first source present: texture (at uvs), colors, palette.
    const float* colors = nullptr;     ///< color_channels per vertex, or per corner (triangle_count * 3 rows)
    int color_channels = 0;            ///< 3 (RGB) or 4 (RGBA)
    int color_stride = 0;              ///< floats per row; 0 = color_channels
    bool colors_per_corner = false;    ///< colors has a row per triangle corner, not per vertex
    bool colors_srgb = false;          ///< sRGB-encoded values (bytes / 255, as in files): decoded to linear
    const Texture* texture = nullptr;  ///< linear texels, sampled at uvs
    const std::uint32_t* material_ids = nullptr;  ///< triangle_count indices into palette
    const float* palette = nullptr;               ///< palette_count * palette_channels, linear
    std::size_t palette_count = 0;                ///< rows of palette
    int palette_channels = 0;                     ///< 3 or 4
    /// Optional, with the palette: palette_count textures (null = that material's flat colour),
    /// each sampled at uvs on its material's triangles instead of the palette colour (OBJ+MTL
    /// map_Kd, as Blender's importer takes it: the image replaces Kd).
    const Texture* const* material_textures = nullptr;
    /// Per-face normals (triangle_count * 3); absent: normals if given, else the geometric normal.
    const float* face_normals = nullptr;
};

/// An axis-aligned box, world units (closed: both corners belong to it).
struct Bounds {
    std::array<double, 3> min{0, 0, 0};  ///< the corner of the smallest x, y, z
    std::array<double, 3> max{0, 0, 0};  ///< the corner of the largest x, y, z
};

/// Sums over the usable triangles that validate() gathers in its pass over them, world units,
/// for the memory estimate (which scales them to the grid instead of reading the triangles
/// again). n is a triangle's cross product (b - a) × (c - a) in double, a its first corner.
struct TriangleSums {
    double crossed_area = 0;  ///< Σ |n|₁ / 2: a plane of area A crosses A·|n̂|₁ / s² cells of side s
    double volume = 0;        ///< Σ (a - bounds.min) · n / 6: the signed volume, apex at bounds.min
    /// Σ n / 6: the signed volume with its apex at p is volume - (p - bounds.min) · normal
    std::array<double, 3> normal{0, 0, 0};
};

/// The result of validate(): the view plus which triangles are usable.
/// Degenerate triangles (a repeated index, or an exactly zero cross product in double
/// precision) are skipped by every backend alike and counted here.
struct ValidatedMesh {
    MeshView view;                      ///< the mesh checked (its arrays are not copied)
    std::vector<std::uint32_t> usable;  ///< indices of non-degenerate triangles, ascending
    std::size_t degenerate_count = 0;   ///< triangles skipped as degenerate
    Bounds bounds;                      ///< of the vertices referenced by usable triangles, world units
    TriangleSums sums;                  ///< over the usable triangles (a tile's part: the whole mesh's)

    /// The position of corner `corner` (0, 1, 2) of triangle `triangle` (an index into the
    /// view's triangles), world units; no checks.
    std::array<float, 3> vertex(std::uint32_t triangle, int corner) const {
        const float* p = view.positions + 3 * std::size_t(view.triangles[3 * std::size_t(triangle) + corner]);
        return {p[0], p[1], p[2]};
    }
};

/// Checks the view and finds its usable triangles, on the calling thread's TBB arena (all
/// cores unless the caller limits it). Reentrant; the view's arrays are only read.
/// @param mesh the mesh to check
/// @param interrupter may be null; asked every 65,536 triangles: a million-triangle mesh takes
///        a noticeable time to check, and Esc / Ctrl-C must not wait for it
/// @throws InvalidInput with a clear message for: null pointers with non-zero counts, an empty
///         mesh, NaN/Inf coordinates (and |x| >= 3.4e38, Inf as Blender stores it), indices out
///         of range, or a mesh whose triangles are all degenerate
/// @throws Cancelled the interrupter asked to stop
ValidatedMesh validate(const MeshView& mesh, Interrupter* interrupter = nullptr);

}  // namespace hyvox
