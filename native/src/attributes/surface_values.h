// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A triangle's attributes at a point of it: colour from the first source the mesh has
// (texture at the interpolated UV, vertex or corner colours, the material palette) and the
// normal (per-face, interpolated per-vertex, or the geometric normal), laid out as the
// channels of AttributeGrid.
#include <array>
#include <cstdint>
#include <vector>

#include "core/attribute_evaluator.h"
#include "hyvox/attribute_grid.h"
#include "hyvox/mesh.h"
#include "hyvox/options.h"
#include "hyvox/texture.h"

namespace hyvox::attributes {

constexpr int kMaxChannels = 7;  // RGB, alpha, normal

// One triangle's values at its three corners, for interpolate(): the per-triangle part of
// evaluate(), done once for all the triangle's pieces.
struct CornerValues {
    double at[3][kMaxChannels];        // each channel at each corner
    const Texture* texture = nullptr;  // set: the colour channels come from it instead, at the
    double uv[3][2];                   //   UV interpolated from these
};

// Final: the exact methods' calls through a SurfaceValues are direct; the tessellation's go
// through AttributeEvaluator.
class SurfaceValues final : public AttributeEvaluator {
public:
    // Throws InvalidInput when colour is asked for and the mesh has no colour source, or a
    // source is malformed (channels, material ids past the palette, non-finite values).
    SurfaceValues(const MeshView& mesh, const AttributeSet& wanted);

    // The grid's layout (values empty).
    const AttributeGrid& layout() const override { return layout_; }
    int channels() const { return layout_.channels(); }

    // The attributes of `triangle` at barycentrics `bary`; `unit_normal` is its geometric
    // normal (used without per-vertex or per-face normals). Writes channels() values.
    void evaluate(std::uint32_t triangle, const std::array<double, 3>& bary, const std::array<double, 3>& unit_normal,
                  double* out) const override;

    // evaluate() in two steps: prepare() once per triangle, interpolate() at each point.
    void prepare(std::uint32_t triangle, const std::array<double, 3>& unit_normal, CornerValues& out) const;
    void interpolate(const CornerValues& corners, const std::array<double, 3>& bary, double* out) const {
        const int channels = layout_.channels();
        for (int n = 0; n < channels; ++n)
            out[n] = bary[0] * corners.at[0][n] + bary[1] * corners.at[1][n] + bary[2] * corners.at[2][n];
        if (corners.texture) sampleTexture(corners, bary, out);
    }
    // sums[n] += weight * the interpolated value of channel n: the weight goes into the
    // barycentrics, and the values go straight into the sums (no array in between).
    void addWeighted(const CornerValues& corners, const std::array<double, 3>& bary, double weight,
                     double* sums) const {
        const int channels = layout_.channels();
        if (corners.texture) {
            double value[kMaxChannels];
            interpolate(corners, bary, value);
            for (int n = 0; n < channels; ++n) sums[n] += weight * value[n];
            return;
        }
        const double w0 = weight * bary[0], w1 = weight * bary[1], w2 = weight * bary[2];
        for (int n = 0; n < channels; ++n)
            sums[n] += w0 * corners.at[0][n] + w1 * corners.at[1][n] + w2 * corners.at[2][n];
    }

private:
    enum class ColorSource { None, Texture, Colors, Palette };
    const float* colorRow(std::uint32_t triangle, int corner) const;
    void sampleTexture(const CornerValues& corners, const std::array<double, 3>& bary, double* out) const;

    const MeshView& mesh_;
    AttributeGrid layout_;
    ColorSource source_ = ColorSource::None;
    int color_channels_ = 0;
    int color_stride_ = 0;              // floats per row of colors_
    std::vector<float> linear_colors_;  // sRGB-encoded colours decoded once
    const float* colors_ = nullptr;     // linear: the mesh's or linear_colors_
};

// A mean normal shorter than this has no direction and is written as zero, as an exact zero
// is. Opposite faces within one voxel (a two-sided wall) cancel exactly in the definition,
// but not in rounding, which would then pick the direction: a random one, different for every
// way of computing the areas, so cpu and hybrid would differ (docs/why/attributes.md).
// Rounding leaves ~1e-16 in double and ~1e-7 from the GL methods' float areas; a real surface
// averaging to this little spans more than 179.99° of normals inside the voxel.
constexpr double kCancelledNormalLength = 1e-5;

// A voxel's value from its weighted sums of values (`sums`, layout.channels() of them): each
// channel's sum over `weight`, the normal as the direction of its sum (zero when the mean
// normal is shorter than kCancelledNormalLength), all zeros when `weight` is not positive.
// Writes layout.channels() values.
void meanOfSums(const AttributeGrid& layout, const double* sums, double weight, float* mean);

}  // namespace hyvox::attributes
