// SPDX-License-Identifier: GPL-3.0-or-later
// Colour and normal voxels in solid mode (attributes/inside_values.h) against a dense brute-force
// version of the rule written here: surface voxels keep the conservative run's values, inside
// voxels of leaves are valued by layers (plain mean of the 26 neighbours valued earlier), each
// whole-brick tile holds the mean of the valued voxels in its one-voxel shell, else of the tiles
// touching it valued earlier. Also: the direct .vdb writer's colour and normal grids (leaves and
// tiles) equal OpenVDB's, and share the density's tree shape.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "attributes/tile_regions.h"
#include "hyvox/vdb.h"
#include "hyvox/voxelize.h"
#include "support/mesh_arrays.h"
#include "support/temp_dir.h"
#include "support/vdb_grid_checks.h"
#include "vdb/vdb_grid.h"

namespace {

using namespace hyvox;

// A closed UV sphere of radius 1 whose vertex colour is a gradient over its position, so that
// every inside value depends on which neighbours were averaged.
struct ColouredSphere {
    std::vector<float> positions, colors;
    std::vector<std::uint32_t> triangles;
    ColouredSphere(int rings = 24, int segments = 48) {
        const double pi = std::acos(-1.0);
        auto add = [&](double x, double y, double z) {
            positions.insert(positions.end(), {float(x), float(y), float(z)});
            colors.insert(colors.end(), {float((x + 1) / 2), float((y + 1) / 2) * 0.5f, float((z + 1) / 2)});
        };
        add(0, 0, 1);
        for (int r = 1; r < rings; ++r)
            for (int s = 0; s < segments; ++s) {
                const double theta = pi * r / rings, phi = 2 * pi * s / segments;
                add(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
            }
        add(0, 0, -1);
        const std::uint32_t last = std::uint32_t(positions.size() / 3 - 1);
        auto ring = [&](int r, int s) { return std::uint32_t(1 + (r - 1) * segments + (s % segments)); };
        for (int s = 0; s < segments; ++s) {
            triangles.insert(triangles.end(), {0, ring(1, s), ring(1, s + 1)});
            triangles.insert(triangles.end(), {last, ring(rings - 1, s + 1), ring(rings - 1, s)});
            for (int r = 1; r + 1 < rings; ++r) {
                triangles.insert(triangles.end(), {ring(r, s), ring(r + 1, s), ring(r + 1, s + 1)});
                triangles.insert(triangles.end(), {ring(r, s), ring(r + 1, s + 1), ring(r, s + 1)});
            }
        }
    }
    MeshView view() const {
        MeshView v = test::viewOf(positions, triangles);
        v.colors = colors.data();
        v.color_channels = 3;
        return v;
    }
};

VoxelizeOptions options(Mode mode, int resolution) {
    VoxelizeOptions o;
    o.method = Method::Cpu;
    o.mode = mode;
    o.grid.resolution = resolution;
    o.attributes = hyvox::parseAttributeSet("color,normal");
    return o;
}

// Dense values (6 channels: colour, normal) of a result, and which voxels it has.
struct Dense {
    std::array<int, 3> dims;
    std::vector<char> set;
    std::vector<double> values;
    std::size_t at(int i, int j, int k) const {
        return (std::size_t(i) * std::size_t(dims[1]) + std::size_t(j)) * std::size_t(dims[2]) + std::size_t(k);
    }
    explicit Dense(const VoxelizeResult& r) : dims{r.grid.dims[0], r.grid.dims[1], r.grid.dims[2]} {
        set.assign(std::size_t(dims[0]) * std::size_t(dims[1]) * std::size_t(dims[2]), 0);
        values.assign(set.size() * 6, 0.0);
        const auto ijk = r.occupancy.coords();
        const std::vector<float> v = valuesInCoordsOrder(r.occupancy, r.attributes);
        EXPECT_EQ(v.size(), ijk.size() * 6);
        for (std::size_t n = 0; n < ijk.size(); ++n) {
            const std::size_t a = at(ijk[n][0], ijk[n][1], ijk[n][2]);
            set[a] = 1;
            for (int c = 0; c < 6; ++c) values[a * 6 + std::size_t(c)] = v[n * 6 + std::size_t(c)];
        }
    }
};

void meanInto(const double* sums, int count, double* out) {
    for (int c = 0; c < 6; ++c) out[c] = sums[c] / count;
    const double length = std::sqrt(out[3] * out[3] + out[4] * out[4] + out[5] * out[5]);
    // Shorter than 1e-5: opposite normals cancelled, no direction (attributes/surface_values.h).
    for (int c = 3; c < 6; ++c) out[c] = length > 1e-5 ? out[c] / length : 0.0;
    for (int c = 0; c < 6; ++c) out[c] = double(float(out[c]));  // stored as float before the next layer
}

TEST(SolidAttributes, InsideValuesFollowTheLayerAndTileRule) {
    const ColouredSphere sphere;
    const VoxelizeResult surface = voxelize(sphere.view(), options(Mode::Conservative, 56));
    const VoxelizeResult solid = voxelize(sphere.view(), options(Mode::Solid, 56));
    const Dense s(surface), d(solid);
    const auto& dims = d.dims;
    // Tile voxels: whole bricks without surface voxels.
    std::vector<char> tile(d.set.size(), 0);
    std::vector<std::array<int, 3>> tile_bricks;
    for (const SparseGrid::TileRun& run : solid.occupancy.tileRuns())
        for (std::uint64_t b = run.begin; b < run.end; ++b) {
            const auto at = solid.occupancy.bricks().at(b);
            bool surface_voxel = false;
            for (int x = 0; x < 8; ++x)
                for (int y = 0; y < 8; ++y)
                    for (int z = 0; z < 8; ++z)
                        surface_voxel = surface_voxel || s.set[d.at(at[0] * 8 + x, at[1] * 8 + y, at[2] * 8 + z)];
            if (surface_voxel) continue;
            tile_bricks.push_back({at[0], at[1], at[2]});
            for (int x = 0; x < 8; ++x)
                for (int y = 0; y < 8; ++y)
                    for (int z = 0; z < 8; ++z) tile[d.at(at[0] * 8 + x, at[1] * 8 + y, at[2] * 8 + z)] = 1;
        }
    ASSERT_GT(tile_bricks.size(), 20u);

    // Leaf layers, Jacobi style on the dense grid.
    std::vector<char> valued = s.set;
    std::vector<double> values = s.values;
    int layers = 0;
    for (;;) {
        std::vector<std::pair<std::size_t, std::array<double, 6>>> fresh;
        for (int i = 0; i < dims[0]; ++i)
            for (int j = 0; j < dims[1]; ++j)
                for (int k = 0; k < dims[2]; ++k) {
                    const std::size_t a = d.at(i, j, k);
                    if (!d.set[a] || tile[a] || valued[a]) continue;
                    double sums[6] = {};
                    int count = 0;
                    for (int dx = -1; dx <= 1; ++dx)
                        for (int dy = -1; dy <= 1; ++dy)
                            for (int dz = -1; dz <= 1; ++dz) {
                                const int x = i + dx, y = j + dy, z = k + dz;
                                if (x < 0 || y < 0 || z < 0 || x >= dims[0] || y >= dims[1] || z >= dims[2]) continue;
                                if (!valued[d.at(x, y, z)]) continue;
                                for (int c = 0; c < 6; ++c) sums[c] += values[d.at(x, y, z) * 6 + std::size_t(c)];
                                ++count;
                            }
                    if (count == 0) continue;
                    std::array<double, 6> mean;
                    meanInto(sums, count, mean.data());
                    fresh.emplace_back(a, mean);
                }
        if (fresh.empty()) break;
        for (const auto& [a, mean] : fresh) {
            valued[a] = 1;
            std::copy(mean.begin(), mean.end(), values.begin() + std::ptrdiff_t(a * 6));
        }
        ++layers;
    }
    std::size_t inside = 0;
    for (std::size_t a = 0; a < d.set.size(); ++a) {
        if (!d.set[a] || tile[a]) continue;
        ASSERT_TRUE(valued[a]) << "a leaf voxel the layers do not reach";
        for (int c = 0; c < 6; ++c)
            ASSERT_NEAR(d.values[a * 6 + std::size_t(c)], values[a * 6 + std::size_t(c)], 1e-5) << a;
        inside += !s.set[a];
    }
    ASSERT_TRUE(solid.stats.solid);
    EXPECT_EQ(solid.stats.solid->attribute_inside_voxels, inside);
    EXPECT_EQ(solid.stats.solid->attribute_layers, std::uint64_t(layers));
    EXPECT_EQ(solid.stats.solid->attribute_fallback, 0u);

    // Tiles: shell means, then tile layers (bricks touching by a face, edge or corner).
    std::map<std::array<int, 3>, std::array<double, 6>> tile_value;
    for (const auto& b : tile_bricks) {
        double sums[6] = {};
        int count = 0;
        for (int x = b[0] * 8 - 1; x <= b[0] * 8 + 8; ++x)
            for (int y = b[1] * 8 - 1; y <= b[1] * 8 + 8; ++y)
                for (int z = b[2] * 8 - 1; z <= b[2] * 8 + 8; ++z) {
                    if (x < 0 || y < 0 || z < 0 || x >= dims[0] || y >= dims[1] || z >= dims[2]) continue;
                    const std::size_t a = d.at(x, y, z);
                    if (tile[a] || !valued[a]) continue;
                    for (int c = 0; c < 6; ++c) sums[c] += values[a * 6 + std::size_t(c)];
                    ++count;
                }
        if (count) meanInto(sums, count, tile_value[b].data());
    }
    int tile_layers = 0;
    while (tile_value.size() < tile_bricks.size()) {
        std::map<std::array<int, 3>, std::array<double, 6>> fresh;
        for (const auto& b : tile_bricks) {
            if (tile_value.count(b)) continue;
            double sums[6] = {};
            int count = 0;
            for (const auto& [other, value] : tile_value) {
                if (std::abs(other[0] - b[0]) > 1 || std::abs(other[1] - b[1]) > 1 || std::abs(other[2] - b[2]) > 1)
                    continue;
                for (int c = 0; c < 6; ++c) sums[c] += value[std::size_t(c)];
                ++count;
            }
            if (count) meanInto(sums, count, fresh[b].data());
        }
        ASSERT_FALSE(fresh.empty()) << "tiles that touch nothing valued";
        tile_value.insert(fresh.begin(), fresh.end());
        ++tile_layers;
    }
    EXPECT_GE(tile_layers, 1) << "the sphere's middle tiles touch only tiles";
    EXPECT_EQ(solid.stats.solid->attribute_region_layers, std::uint64_t(tile_layers));
    for (const auto& [b, value] : tile_value)
        for (int x = 0; x < 8; ++x)
            for (int c = 0; c < 6; ++c)
                ASSERT_NEAR(d.values[d.at(b[0] * 8 + x, b[1] * 8 + 7 - x, b[2] * 8 + x) * 6 + std::size_t(c)],
                            value[std::size_t(c)], 1e-5);
}

TEST(SolidAttributes, ThreadsAndTilingChangeNothing) {
    const ColouredSphere sphere;
    VoxelizeOptions one = options(Mode::Solid, 72), other = one;
    one.threads = 1;
    other.threads = 3;
    other.tile_size = 24;
    const VoxelizeResult a = voxelize(sphere.view(), one), b = voxelize(sphere.view(), other);
    EXPECT_EQ(a.occupancy, b.occupancy);
    EXPECT_EQ(a.attributes.values, b.attributes.values);
    EXPECT_EQ(a.attributes.valued_tile_bricks, b.attributes.valued_tile_bricks);
    ASSERT_EQ(a.attributes.tiles.size(), b.attributes.tiles.size());
    for (std::size_t n = 0; n < a.attributes.tiles.size(); ++n) {
        EXPECT_EQ(a.attributes.tiles[n].origin, b.attributes.tiles[n].origin);
        EXPECT_EQ(a.attributes.tiles[n].values, b.attributes.tiles[n].values);
    }
}

TEST(SolidAttributes, DirectFileEqualsOpenVdbsAndSharesTheDensitysTree) {
    const ColouredSphere sphere;
    // 72 voxels across: tiles of level 1 only (test_solid_attributes.py checks a 128³ one).
    const VoxelizeResult r = voxelize(sphere.view(), options(Mode::Solid, 72));
    ASSERT_FALSE(r.attributes.tiles.empty());
    ASSERT_FALSE(r.attributes.valued_tile_bricks.empty()) << "whole bricks holding surface voxels";
    test::TempDir dir;
    const std::string direct_path = (dir.path / "direct.vdb").string(),
                      reference_path = (dir.path / "openvdb.vdb").string();
    writeVdb(r, direct_path);
    const openvdb::GridPtrVec grids = vdb::makeGrids(r);
    vdb::writeGridsAtomic(openvdb::GridCPtrVec(grids.begin(), grids.end()), reference_path);
    vdb::initializeOpenVdb();
    const auto density = test::readVdbGrid<openvdb::FloatGrid>(direct_path, "density");
    ASSERT_TRUE(density);
    test::expectSameGrids(*density, *test::readVdbGrid<openvdb::FloatGrid>(reference_path, "density"));
    EXPECT_EQ(density->activeVoxelCount(), openvdb::Index64(r.occupancy.count()));
    for (const char* name : {"color", "normal"}) {
        SCOPED_TRACE(name);
        const auto direct = test::readVdbGrid<openvdb::Vec3SGrid>(direct_path, name);
        const auto reference = test::readVdbGrid<openvdb::Vec3SGrid>(reference_path, name);
        ASSERT_TRUE(direct && reference);
        test::expectSameGrids(*direct, *reference);
        EXPECT_EQ(direct->activeVoxelCount(), density->activeVoxelCount());
        EXPECT_EQ(direct->tree().leafCount(), density->tree().leafCount());
        EXPECT_EQ(direct->tree().activeTileCount(), density->tree().activeTileCount());
    }
}

}  // namespace

namespace {

// Tile bricks [lo, hi) (in bricks) added as runs along z.
void addTileBox(SparseGrid& grid, std::array<int, 3> lo, std::array<int, 3> hi) {
    for (int x = lo[0]; x < hi[0]; ++x)
        for (int y = lo[1]; y < hi[1]; ++y)
            grid.addTileRun(grid.bricks().index(x, y, lo[2]), grid.bricks().index(x, y, hi[2] - 1) + 1);
}

}  // namespace

TEST(SolidAttributes, TileRegionsAreOpenVdbsPrunedTiles) {
    // A 4096³ node wholly tiles (level 3), a 128³ node beside it (level 2), a 128³ node with one
    // brick valued voxel by voxel (4095 level-1 regions), and a lone brick.
    SparseGrid grid({8192, 4224, 4104});
    addTileBox(grid, {0, 0, 0}, {512, 512, 512});
    addTileBox(grid, {512, 0, 0}, {528, 16, 16});
    addTileBox(grid, {512, 32, 0}, {528, 48, 16});
    addTileBox(grid, {700, 20, 3}, {701, 21, 4});
    grid.finish();
    const std::vector<std::uint64_t> valued{grid.bricks().index(515, 40, 7)};
    const attributes::TileRegions regions(grid, valued);
    const auto& all = regions.regions();
    ASSERT_EQ(all.size(), 1u + 1u + 4095u + 1u);
    std::map<int, int> levels;
    for (const auto& r : all) ++levels[r.level];
    EXPECT_EQ(levels[3], 1);
    EXPECT_EQ(levels[2], 1);
    EXPECT_EQ(levels[1], 4096);
    const std::int64_t top = regions.at(0, 0, 0), node = regions.at(520, 5, 5), lone = regions.at(700, 20, 3);
    EXPECT_EQ(regions.at(511, 511, 511), top);
    EXPECT_EQ(all[std::size_t(top)].level, 3);
    EXPECT_EQ(all[std::size_t(node)].level, 2);
    EXPECT_EQ(regions.at(512, 0, 0), node);
    EXPECT_EQ(regions.at(515, 40, 7), -1) << "a valued brick is no region";
    EXPECT_EQ(regions.at(699, 20, 3), -1);
    EXPECT_EQ(all[std::size_t(lone)].level, 1);
    EXPECT_TRUE(regions.neighbours(lone).empty());
    // The 128³ node touches the 4096³ one (face x = 4096) and nothing else.
    EXPECT_EQ(regions.neighbours(node), std::vector<std::int64_t>{top});
    const auto around_top = regions.neighbours(top);
    EXPECT_EQ(around_top.size(), 1u + 16u * 16u) << "the 128³ node and the other node's bricks on its face";
    // A brick next to the valued one: its 25 tile neighbours (the valued brick is not one).
    EXPECT_EQ(regions.neighbours(regions.at(516, 40, 7)).size(), 25u);
}
