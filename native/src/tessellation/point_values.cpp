// SPDX-License-Identifier: GPL-3.0-or-later
#include "tessellation/point_values.h"

#include "attributes/clip_to_voxel.h"
#include "attributes/surface_values.h"
#include "hyvox/errors.h"

namespace hyvox::tessellation {

std::string PointValues::defines() const {
    std::string text = "#define ATTRIBUTES 1\n#define ATTRIBUTE_CHANNELS " + std::to_string(channels()) +
        "\n#define VALUE_SCALE " + std::to_string(kValueScale) + "\n#define VALUE_LIMIT " +
        std::to_string(kValueLimit) + "\n";
    if (texture)
        text += "#define TEXTURE_COLOR 1\n#define COLOR_CHANNELS " + std::string(layout.alpha ? "4" : "3") + "\n";
    return text;
}

PointValues makePointValues(const ValidatedMesh& mesh, const GridSpec& grid, const AttributeEvaluator& values) {
    PointValues out;
    out.layout = values.layout();
    // The shaders sample one texture; a texture per material (OBJ map_Kd) is the exact methods'.
    if (out.layout.color && mesh.view.material_textures && !mesh.view.texture && !mesh.view.colors)
        for (std::size_t m = 0; m < mesh.view.palette_count; ++m)
            if (mesh.view.material_textures[m])
                throw InvalidInput(
                    "the tessellation method samples one texture, not one per material: use the cpu "
                    "method for these materials' images");
    // SurfaceValues takes the texture first whenever the mesh has one (it refuses one without UVs).
    if (out.layout.color && mesh.view.texture) out.texture = mesh.view.texture;
    const std::size_t channels = std::size_t(out.channels());
    out.corners.resize(mesh.usable.size() * 3 * channels);
    double value[attributes::kMaxChannels];
    for (std::size_t u = 0; u < mesh.usable.size(); ++u) {
        const std::uint32_t triangle = mesh.usable[u];
        const std::array<std::array<double, 3>, 3> p = {grid.toVoxel(mesh.vertex(triangle, 0)),
                                                        grid.toVoxel(mesh.vertex(triangle, 1)),
                                                        grid.toVoxel(mesh.vertex(triangle, 2))};
        const attributes::TriangleFrame frame(p);  // for its unit normal
        for (std::size_t c = 0; c < 3; ++c) {
            std::array<double, 3> corner{0, 0, 0};
            corner[c] = 1;
            values.evaluate(triangle, corner, frame.unitNormal(), value);
            float* row = &out.corners[(3 * u + c) * channels];
            for (std::size_t n = 0; n < channels; ++n) row[n] = float(value[n]);
            if (out.texture) {
                const std::uint32_t vertex = mesh.view.triangles[3 * std::size_t(triangle) + c];
                row[0] = mesh.view.uvs[2 * std::size_t(vertex)];
                row[1] = mesh.view.uvs[2 * std::size_t(vertex) + 1];
            }
        }
    }
    return out;
}

std::uint64_t meansFromSums(const std::vector<std::uint32_t>& brick_blocks,
                            const std::vector<std::uint32_t>& count_pool, const std::vector<std::uint32_t>& value_pool,
                            const BitGrid& bits, const std::array<std::int32_t, 3>& tile_offset, const GridSpec& grid,
                            const AttributeGrid& layout, std::vector<AttributeLeaf>& out) {
    const BrickLayout& tile_bricks = bits.bricks();
    const BrickLayout grid_bricks = grid.bricks();
    const int channels = layout.channels();
    std::uint64_t unreached = 0;
    for (std::size_t brick = 0; brick < tile_bricks.total(); ++brick) {
        const std::uint64_t* words = bits.data() + brick * BitGrid::kWordsPerBrick;
        bool any = false;
        for (int w = 0; w < BitGrid::kWordsPerBrick; ++w) any = any || words[w] != 0;
        if (!any) continue;
        const std::array<std::int32_t, 3> at = tile_bricks.at(brick);
        AttributeLeaf& leaf = out.emplace_back();
        leaf.brick = grid_bricks.index((tile_offset[0] >> 3) + at[0], (tile_offset[1] >> 3) + at[1],
                                       (tile_offset[2] >> 3) + at[2]);
        const std::uint64_t block = brick < brick_blocks.size() ? brick_blocks[brick] : 0;
        const bool held =
            block != 0 && block * 512 <= count_pool.size() && block * valueWordsPerBlock(channels) <= value_pool.size();
        for (int n = 0; n < 512; ++n) {
            if (!((words[n >> 6] >> (n & 63)) & 1u)) continue;
            const std::uint32_t count = held ? count_pool[(block - 1) * 512 + std::size_t(n)] : 0;
            double exact[attributes::kMaxChannels] = {};
            if (count == 0) {
                ++unreached;
            } else {
                const std::uint32_t* sum =
                    &value_pool[((block - 1) * 512 + std::size_t(n)) * 2 * std::size_t(channels)];
                for (int c = 0; c < channels; ++c) {
                    const std::uint64_t bits64 = (std::uint64_t(sum[2 * c + 1]) << 32) | sum[2 * c];
                    exact[c] = double(std::int64_t(bits64)) / kValueScale;
                }
            }
            float mean[attributes::kMaxChannels];
            attributes::meanOfSums(layout, exact, double(count), mean);
            leaf.values.insert(leaf.values.end(), mean, mean + channels);
        }
    }
    return unreached;
}

}  // namespace hyvox::tessellation
