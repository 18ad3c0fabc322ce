// SPDX-License-Identifier: GPL-3.0-or-later
#include "attributes/surface_values.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "hyvox/errors.h"

namespace hyvox::attributes {
namespace {

void requireFinite(const float* values, std::size_t count, const char* name) {
    for (std::size_t n = 0; n < count; ++n)
        if (!std::isfinite(values[n])) throw InvalidInput(std::string(name) + " contain NaN or Inf");
}

// srgbToLinear in float. Colours from bytes (k / 255 in float, as files and the Python front
// door give them) take a table of the same values instead of a pow each.
float decodeSrgb(float encoded) {
    static const std::array<float, 256> of_byte = [] {
        std::array<float, 256> table{};
        for (int k = 0; k < 256; ++k) table[std::size_t(k)] = float(srgbToLinear(double(float(k) / 255.0f)));
        return table;
    }();
    const float byte = encoded * 255.0f;
    if (byte >= 0.0f && byte <= 255.0f && byte == float(int(byte)) && float(int(byte)) / 255.0f == encoded)
        return of_byte[std::size_t(int(byte))];
    return float(srgbToLinear(encoded));
}

}  // namespace

SurfaceValues::SurfaceValues(const MeshView& mesh, const AttributeSet& wanted) : mesh_(mesh) {
    if (wanted.color) {
        if (mesh.texture && mesh.uvs) {
            source_ = ColorSource::Texture;
            color_channels_ = mesh.texture->channels;
        } else if (mesh.texture) {
            throw InvalidInput("a texture needs the mesh's UVs (per-vertex u, v)");
        } else if (mesh.colors) {
            source_ = ColorSource::Colors;
            color_channels_ = mesh.color_channels;
            if (color_channels_ != 3 && color_channels_ != 4)
                throw InvalidInput("colours have 3 (RGB) or 4 (RGBA) channels, got " + std::to_string(color_channels_));
            color_stride_ = mesh.color_stride > 0 ? mesh.color_stride : color_channels_;
            if (color_stride_ < color_channels_)
                throw InvalidInput("colour rows of " + std::to_string(color_stride_) + " values cannot hold " +
                                   std::to_string(color_channels_) + " channels");
            const std::size_t rows = mesh.colors_per_corner ? 3 * mesh.triangle_count : mesh.vertex_count;
            const std::size_t count = rows * std::size_t(color_stride_);
            requireFinite(mesh.colors, count, "colours");
            colors_ = mesh.colors;
            if (mesh.colors_srgb) {
                linear_colors_.assign(mesh.colors, mesh.colors + count);
                for (std::size_t n = 0; n < count; ++n)
                    if (n % std::size_t(color_stride_) < 3) linear_colors_[n] = decodeSrgb(linear_colors_[n]);
                colors_ = linear_colors_.data();
            }
        } else if (mesh.palette && mesh.material_ids) {
            source_ = ColorSource::Palette;
            color_channels_ = mesh.palette_channels;
            if (color_channels_ != 3 && color_channels_ != 4)
                throw InvalidInput("palette colours have 3 (RGB) or 4 (RGBA) channels, got " +
                                   std::to_string(color_channels_));
            requireFinite(mesh.palette, mesh.palette_count * std::size_t(color_channels_), "palette colours");
            for (std::size_t t = 0; t < mesh.triangle_count; ++t)
                if (mesh.material_ids[t] >= mesh.palette_count)
                    throw InvalidInput("triangle " + std::to_string(t) + " has material id " +
                                       std::to_string(mesh.material_ids[t]) + ", but the palette has " +
                                       std::to_string(mesh.palette_count) + " colours");
            if (mesh.material_textures && !mesh.uvs)
                for (std::size_t m = 0; m < mesh.palette_count; ++m)
                    if (mesh.material_textures[m])
                        throw InvalidInput("material " + std::to_string(m) +
                                           " has a texture, which needs the mesh's UVs");
        } else {
            throw InvalidInput(
                "attributes: color needs a colour source: vertex or corner colours, UVs and a texture, or material "
                "ids and a palette");
        }
        layout_.color = true;
        layout_.alpha = color_channels_ == 4;
    }
    if (wanted.normal) {
        layout_.normal = true;
        if (mesh.face_normals) requireFinite(mesh.face_normals, 3 * mesh.triangle_count, "face normals");
    }
}

const float* SurfaceValues::colorRow(std::uint32_t triangle, int corner) const {
    const std::size_t row = mesh_.colors_per_corner
        ? 3 * std::size_t(triangle) + std::size_t(corner)
        : std::size_t(mesh_.triangles[3 * std::size_t(triangle) + std::size_t(corner)]);
    return colors_ + row * std::size_t(color_stride_);
}

void SurfaceValues::prepare(std::uint32_t triangle, const std::array<double, 3>& unit_normal, CornerValues& out) const {
    const std::uint32_t* index = mesh_.triangles + 3 * std::size_t(triangle);
    out.texture = nullptr;
    int offset = 0;
    if (layout_.color) {
        const int written = layout_.alpha ? 4 : 3;
        switch (source_) {
            case ColorSource::Texture: out.texture = mesh_.texture; break;
            case ColorSource::Colors:
                for (int c = 0; c < 3; ++c) {
                    const float* row = colorRow(triangle, c);
                    for (int n = 0; n < written; ++n) out.at[c][n] = row[n];
                }
                break;
            case ColorSource::Palette: {
                const std::uint32_t material = mesh_.material_ids[triangle];
                const float* entry = mesh_.palette + std::size_t(material) * std::size_t(color_channels_);
                for (int c = 0; c < 3; ++c)
                    for (int n = 0; n < written; ++n) out.at[c][n] = entry[n];
                if (mesh_.material_textures) out.texture = mesh_.material_textures[material];
                break;
            }
            case ColorSource::None: break;
        }
        if (out.texture)
            for (int c = 0; c < 3; ++c) {
                out.uv[c][0] = mesh_.uvs[2 * std::size_t(index[c])];
                out.uv[c][1] = mesh_.uvs[2 * std::size_t(index[c]) + 1];
                for (int n = 0; n < written; ++n) out.at[c][n] = 0;  // replaced by the texture's
            }
        offset = written;
    }
    if (layout_.normal)
        for (int c = 0; c < 3; ++c) {
            double* normal = &out.at[c][offset];
            for (std::size_t a = 0; a < 3; ++a)
                normal[a] = mesh_.face_normals ? double(mesh_.face_normals[3 * std::size_t(triangle) + a])
                    : mesh_.normals            ? double(mesh_.normals[3 * std::size_t(index[c]) + a])
                                               : unit_normal[a];
        }
}

void SurfaceValues::sampleTexture(const CornerValues& corners, const std::array<double, 3>& bary, double* out) const {
    double u = 0, v = 0;
    for (int c = 0; c < 3; ++c) {
        u += bary[std::size_t(c)] * corners.uv[c][0];
        v += bary[std::size_t(c)] * corners.uv[c][1];
    }
    const std::array<float, 4> texel = corners.texture->sample(u, v);
    for (int n = 0; n < (layout_.alpha ? 4 : 3); ++n) out[n] = texel[std::size_t(n)];
}

void SurfaceValues::evaluate(std::uint32_t triangle, const std::array<double, 3>& bary,
                             const std::array<double, 3>& unit_normal, double* out) const {
    CornerValues corners;
    prepare(triangle, unit_normal, corners);
    interpolate(corners, bary, out);
}

void meanOfSums(const AttributeGrid& layout, const double* sums, double weight, float* mean) {
    const int channels = layout.channels();
    if (!(weight > 0)) {
        std::fill(mean, mean + channels, 0.0f);
        return;
    }
    // The weight's reciprocal (at least 1e-6): one division per voxel instead of one per
    // channel, a few ulp in double, far below the float the mean is stored in.
    const double inverse_weight = 1.0 / weight;
    for (int c = 0; c < channels; ++c) mean[c] = float(sums[c] * inverse_weight);
    if (!layout.normal) return;
    const double* n = sums + layout.normalOffset();
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const bool direction = length > kCancelledNormalLength * weight;  // the mean's length over the line
    const double inverse_length = direction ? 1.0 / length : 0.0;     // one division, as for the weight
    for (int a = 0; a < 3; ++a) mean[layout.normalOffset() + a] = direction ? float(n[a] * inverse_length) : 0.0f;
}

}  // namespace hyvox::attributes
