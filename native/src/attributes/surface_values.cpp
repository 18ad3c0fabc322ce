// SPDX-License-Identifier: GPL-3.0-or-later
#include "attributes/surface_values.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "hyvox/errors.h"
#include "hyvox/texture.h"

namespace hyvox::attributes {
namespace {

void requireFinite(const float* values, std::size_t count, const char* name) {
    for (std::size_t n = 0; n < count; ++n)
        if (!std::isfinite(values[n])) throw InvalidInput(std::string(name) + " contain NaN or Inf");
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
                    if (n % std::size_t(color_stride_) < 3) linear_colors_[n] = float(srgbToLinear(linear_colors_[n]));
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
    const std::size_t row = mesh_.colors_per_corner ? 3 * std::size_t(triangle) + std::size_t(corner)
                                                    : std::size_t(mesh_.triangles[3 * std::size_t(triangle) + std::size_t(corner)]);
    return colors_ + row * std::size_t(color_stride_);
}

void SurfaceValues::evaluate(std::uint32_t triangle, const std::array<double, 3>& bary,
                             const std::array<double, 3>& unit_normal, double* out) const {
    const std::uint32_t* index = mesh_.triangles + 3 * std::size_t(triangle);
    if (layout_.color) {
        double rgba[4] = {0, 0, 0, 1};
        switch (source_) {
            case ColorSource::Texture: {
                double u = 0, v = 0;
                for (int c = 0; c < 3; ++c) {
                    u += bary[std::size_t(c)] * double(mesh_.uvs[2 * std::size_t(index[c])]);
                    v += bary[std::size_t(c)] * double(mesh_.uvs[2 * std::size_t(index[c]) + 1]);
                }
                const std::array<float, 4> texel = mesh_.texture->sample(u, v);
                for (int n = 0; n < 4; ++n) rgba[n] = texel[std::size_t(n)];
                break;
            }
            case ColorSource::Colors:
                for (int n = 0; n < color_channels_; ++n) {
                    rgba[n] = 0;
                    for (int c = 0; c < 3; ++c) rgba[n] += bary[std::size_t(c)] * double(colorRow(triangle, c)[n]);
                }
                break;
            case ColorSource::Palette: {
                const float* entry = mesh_.palette + std::size_t(mesh_.material_ids[triangle]) * std::size_t(color_channels_);
                for (int n = 0; n < color_channels_; ++n) rgba[n] = entry[n];
                break;
            }
            case ColorSource::None: break;
        }
        for (int n = 0; n < (layout_.alpha ? 4 : 3); ++n) *out++ = rgba[n];
    }
    if (layout_.normal) {
        if (mesh_.face_normals) {
            for (std::size_t a = 0; a < 3; ++a) out[a] = mesh_.face_normals[3 * std::size_t(triangle) + a];
        } else if (mesh_.normals) {
            for (std::size_t a = 0; a < 3; ++a) {
                out[a] = 0;
                for (int c = 0; c < 3; ++c) out[a] += bary[std::size_t(c)] * double(mesh_.normals[3 * std::size_t(index[c]) + a]);
            }
        } else {
            for (std::size_t a = 0; a < 3; ++a) out[a] = unit_normal[a];
        }
    }
}

void meanOfSums(const AttributeGrid& layout, const double* sums, double weight, float* mean) {
    const int channels = layout.channels();
    if (!(weight > 0)) {
        std::fill(mean, mean + channels, 0.0f);
        return;
    }
    for (int c = 0; c < channels; ++c) mean[c] = float(sums[c] / weight);
    if (!layout.normal) return;
    const double* n = sums + layout.normalOffset();
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int a = 0; a < 3; ++a) mean[layout.normalOffset() + a] = length > 0 ? float(n[a] / length) : 0.0f;
}

}  // namespace hyvox::attributes
