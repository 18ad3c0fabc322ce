# SPDX-License-Identifier: GPL-3.0-or-later
# Colour and normal voxels in solid mode (native/src/attributes/inside_values.h) against a numpy
# oracle of the definition: the surface voxels keep the conservative run's values, the inside
# voxels held in leaves are valued by layers from the surface inward (the plain mean of the
# 26-neighbours valued in earlier layers), and each tile region holds the mean of the valued
# voxels in its one-voxel shell, or else the mean of the regions touching it valued earlier.
# The oracle takes from the run only the surface values (the conservative run of the same
# method), the solid's voxels and which of them the .vdb holds as tiles; it propagates itself.
import numpy as np
import pyopenvdb as vdb
import pytest

import hyvox
from attribute_oracle import CANCELLED_NORMAL_LENGTH
from shapes import icosphere

NAMES = ("color", "alpha", "normal")
NEIGHBOURS = [(dx, dy, dz) for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1) if (dx, dy, dz) != (0, 0, 0)]


def dense_values(grid, dims):
    """The grid's voxels as a bool array and its attributes as one float64 array (dims + (channels,))."""
    ijk = grid.coords()
    arrays = grid.attributes()
    names = [n for n in NAMES if n in arrays]
    columns = np.concatenate([arrays[n].reshape(len(ijk), -1) for n in names], axis=1).astype(np.float64)
    mask = np.zeros(dims, bool)
    values = np.zeros(tuple(dims) + (columns.shape[1],))
    mask[ijk[:, 0], ijk[:, 1], ijk[:, 2]] = True
    values[ijk[:, 0], ijk[:, 1], ijk[:, 2]] = columns
    return mask, values, names


def normal_slice(names, arrays):
    """Columns of the normal in the concatenated channels, or None."""
    at = 0
    for name in names:
        width = 1 if name == "alpha" else 3
        if name == "normal":
            return slice(at, at + width)
        at += width
    return None


def mean_of(sums, count, normal):
    value = sums / count
    if normal is not None:
        n = value[..., normal]
        length = np.linalg.norm(n, axis=-1, keepdims=True)
        direction = length > CANCELLED_NORMAL_LENGTH  # shorter: opposite normals cancelled, zero
        value[..., normal] = np.where(direction, n / np.where(direction, length, 1), 0)
    return value


def read_tiles(path, name):
    """{(min, max): value} of the active tiles of grid `name`, and its active voxel count."""
    grid = vdb.read(str(path), name)
    tiles = {}
    for item in grid.citerOnValues():
        if item.count > 1:
            tiles[(tuple(item.min), tuple(item.max))] = np.atleast_1d(np.asarray(item.value, np.float64))
    return tiles, grid.activeVoxelCount()


def leaf_layers(valued, values, leaf, normal):
    """The oracle of the leaf layers: returns values, valued, layers."""
    valued, values = valued.copy(), values.copy()
    pending = leaf & ~valued
    layers = 0
    while True:
        padded_valued = np.pad(valued, 1)
        padded_values = np.pad(values * valued[..., None], ((1, 1), (1, 1), (1, 1), (0, 0)))
        count = np.zeros(valued.shape)
        sums = np.zeros(values.shape)
        d = valued.shape
        for dx, dy, dz in NEIGHBOURS:
            window = (slice(1 + dx, 1 + dx + d[0]), slice(1 + dy, 1 + dy + d[1]), slice(1 + dz, 1 + dz + d[2]))
            count += padded_valued[window]
            sums += padded_values[window]
        fresh = pending & (count > 0)
        if not fresh.any():
            return values, valued, layers
        # Rounded to float32 as the run stores each layer before the next reads it.
        values[fresh] = mean_of(sums[fresh], count[fresh][:, None], normal).astype(np.float32)
        valued |= fresh
        pending &= ~fresh
        layers += 1


def tile_oracle(tiles, valued, values, normal):
    """Each tile box's value: its shell mean over valued voxels, else by tile layers."""
    boxes = list(tiles)
    value = {}
    for box in boxes:
        lo, hi = np.array(box[0]), np.array(box[1])
        a, b = np.maximum(lo - 1, 0), hi + 2
        shell = valued[a[0] : b[0], a[1] : b[1], a[2] : b[2]].copy()
        inner_lo, inner_hi = lo - a, hi - a + 1
        shell[inner_lo[0] : inner_hi[0], inner_lo[1] : inner_hi[1], inner_lo[2] : inner_hi[2]] = False
        if shell.any():
            chosen = values[a[0] : b[0], a[1] : b[1], a[2] : b[2]][shell]
            value[box] = mean_of(chosen.sum(axis=0), len(chosen), normal)

    def touching(p, q):
        return all(p[0][k] <= q[1][k] + 1 and q[0][k] <= p[1][k] + 1 for k in range(3))

    layers = 0
    while len(value) < len(boxes):
        fresh = {}
        for box in boxes:
            if box in value:
                continue
            near = [value[other] for other in boxes if other in value and other != box and touching(box, other)]
            if near:
                fresh[box] = mean_of(np.sum(near, axis=0), len(near), normal).astype(np.float32)
        assert fresh, "tile regions that touch nothing valued"
        value.update(fresh)
        layers += 1
    return value, layers


def check_solid_attributes(v, t, tmp_path, *, method, resolution, **colour):
    """Runs conservative and solid with colour and normal; checks the solid against the oracle.
    Returns the solid grid."""
    kw = dict(resolution=resolution, method=method, attributes="color,normal", **colour)
    surface = hyvox.voxelize(v, t, mode="conservative", **kw)
    solid = hyvox.voxelize(v, t, mode="solid", **kw)
    dims = tuple(solid.dims)
    assert tuple(surface.dims) == dims
    path = tmp_path / f"solid_{method}.vdb"
    solid.write_vdb(str(path))

    surface_mask, surface_values, names = dense_values(surface, dims)
    solid_mask, solid_values, solid_names = dense_values(solid, dims)
    assert names == solid_names
    normal = normal_slice(names, solid.attributes())

    # Every grid has exactly the density's voxels and tiles.
    density_tiles, density_count = read_tiles(path, "density")
    assert density_count == solid.voxel_count
    written = [g.name for g in vdb.readAllGridMetadata(str(path))]
    for name in names:
        assert name in written
        tiles, count = read_tiles(path, name)
        assert count == density_count, name
        assert sorted(tiles) == sorted(density_tiles), name

    # Surface voxels keep the conservative run's values.
    assert not (surface_mask & ~solid_mask).any()
    np.testing.assert_allclose(solid_values[surface_mask], surface_values[surface_mask], rtol=0, atol=1e-6)

    # Tile voxels (whole bricks of the .vdb) and leaf voxels.
    tile_mask = np.zeros(dims, bool)
    for lo, hi in density_tiles:
        tile_mask[lo[0] : hi[0] + 1, lo[1] : hi[1] + 1, lo[2] : hi[2] + 1] = True
    assert not (tile_mask & surface_mask).any(), "surface voxels lie in leaves"
    leaf = solid_mask & ~tile_mask
    values, valued, layers = leaf_layers(surface_mask, surface_values, leaf, normal)
    assert not (leaf & ~valued).any(), "leaf voxels the layers do not reach"
    inside_leaf = leaf & ~surface_mask
    assert inside_leaf.sum() > 0
    np.testing.assert_allclose(solid_values[inside_leaf], values[inside_leaf], rtol=0, atol=1e-5)

    stats = solid.stats["solid"]
    assert stats["attribute_inside_voxels"] == inside_leaf.sum()
    assert stats["attribute_layers"] == layers
    assert stats["attribute_fallback"] == 0 and stats["attribute_through_regions"] == 0

    # Tiles: the .vdb's tile values, and each tile voxel's row in the Python arrays.
    expected, tile_layers = tile_oracle(density_tiles, valued, values, normal)
    assert stats["attribute_tile_regions"] == len(density_tiles)
    assert stats["attribute_region_layers"] == tile_layers
    for at, name in enumerate(names):
        width = 1 if name == "alpha" else 3
        start = sum(1 if n == "alpha" else 3 for n in names[:at])
        tiles, _ = read_tiles(path, name)
        for box, value in expected.items():
            np.testing.assert_allclose(tiles[box], value[start : start + width], rtol=0, atol=1e-5, err_msg=name)
    for (lo, hi), value in expected.items():
        block = solid_values[lo[0] : hi[0] + 1, lo[1] : hi[1] + 1, lo[2] : hi[2] + 1]
        np.testing.assert_allclose(block.reshape(-1, block.shape[-1]) - value, 0, atol=1e-5)
    return solid, density_tiles, tile_layers


@pytest.fixture(scope="module")
def spot_vcolor(mesh_dir):
    v, t, attrs = hyvox.read_mesh(mesh_dir / "spot_vcolor.ply", attributes=True)
    return v, t, (attrs["colors"][:, :3] * 255).round().astype(np.uint8)


def two_colour_sphere():
    """A closed sphere, red above z = 0 and blue below (linear float colours)."""
    v, t = icosphere(3)
    colors = np.where(v[:, 2:3] > 0, np.float32([0.9, 0.1, 0.1]), np.float32([0.1, 0.2, 0.9])).astype(np.float32)
    return v, t, colors


@pytest.mark.parametrize("method", ["cpu", "hybrid"])
@pytest.mark.parametrize("resolution", [48, 64])
def test_spot_solid_colours_follow_the_layer_rule(spot_vcolor, tmp_path, method, resolution):
    v, t, colors = spot_vcolor
    solid, tiles, _ = check_solid_attributes(v, t, tmp_path, method=method, resolution=resolution, colors=colors)
    assert solid.attributes()["color"].std(axis=0).min() > 0.02  # not flat: a wrong neighbour would show
    if resolution == 64:
        assert tiles, "spot at 64 has whole-brick tiles"


@pytest.mark.parametrize("method", ["cpu", "reference", "triangle", "fragment"])
def test_two_colour_sphere_fills_with_tiles_and_tile_layers(tmp_path, method):
    v, t, colors = two_colour_sphere()
    solid, tiles, tile_layers = check_solid_attributes(v, t, tmp_path, method=method, resolution=64, colors=colors)
    assert len(tiles) > 10 and tile_layers >= 1, "the sphere's middle tiles touch only tiles"
    # The upper half is red inside too, the lower half blue.
    ijk, color = solid.coords(), solid.attributes()["color"]
    z = ijk[:, 2] - solid.dims[2] / 2
    assert np.all(color[z > 3][:, 0] > 0.5) and np.all(color[z < -3][:, 2] > 0.5)


def test_tessellation_surface_values_are_its_own(spot_vcolor, tmp_path):
    # The approximate method: its surface voxels keep its own averages, the rest follows the rule.
    v, t, colors = spot_vcolor
    check_solid_attributes(v, t, tmp_path, method="tessellation", resolution=48, colors=colors)


def test_values_do_not_depend_on_threads_or_tiling(spot_vcolor):
    v, t, colors = spot_vcolor
    kw = dict(resolution=80, method="cpu", mode="solid", colors=colors, attributes="color,normal")
    one = hyvox.voxelize(v, t, threads=1, **kw)
    other = hyvox.voxelize(v, t, threads=2, tile_size=24, **kw)
    assert np.array_equal(one.coords(), other.coords())
    for name in ("color", "normal"):
        assert np.array_equal(one.attributes()[name], other.attributes()[name]), name


def test_alpha_is_valued_like_colour(tmp_path):
    v, t, colors = two_colour_sphere()
    rgba = np.concatenate([colors, np.where(v[:, 2:3] > 0, 1.0, 0.25).astype(np.float32)], axis=1)
    solid, _, _ = check_solid_attributes(v, t, tmp_path, method="cpu", resolution=40, colors=rgba)
    assert "alpha" in solid.attributes()


def test_bad_attribute_input_in_solid_mode_is_a_clear_error():
    v, t, _ = two_colour_sphere()
    with pytest.raises(ValueError, match="color"):
        hyvox.voxelize(v, t, resolution=16, mode="solid", attributes="color")  # no colour source
    with pytest.raises(ValueError, match="unknown attribute"):
        hyvox.voxelize(v, t, resolution=16, mode="solid", attributes="colour")


def test_a_128_node_wholly_inside_is_one_tile_in_every_grid(tmp_path):
    # A cube of 264 voxels holds the 128³ node [128, 256)³ wholly inside: OpenVDB prunes the
    # density's bricks there into one level-2 tile, and the colour and normal grids must hold
    # the same tile (one value), not 4096 tiles or 2 million voxels.
    v = np.array([(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)], np.float32)
    t = np.array(
        [
            (0, 1, 3),
            (0, 3, 2),
            (4, 6, 7),
            (4, 7, 5),
            (0, 4, 5),
            (0, 5, 1),
            (2, 3, 7),
            (2, 7, 6),
            (0, 2, 6),
            (0, 6, 4),
            (1, 5, 7),
            (1, 7, 3),
        ],
        np.uint32,
    )
    colors = np.tile(np.float32([0.3, 0.6, 0.1]), (8, 1))
    solid = hyvox.voxelize(v, t, resolution=264, method="cpu", mode="solid", colors=colors, attributes="color,normal")
    path = tmp_path / "cube.vdb"
    solid.write_vdb(str(path))
    density_tiles, count = read_tiles(path, "density")
    big = [box for box in density_tiles if np.all(np.subtract(box[1], box[0]) == 127)]
    assert big == [((128, 128, 128), (255, 255, 255))]
    for name in ("color", "normal"):
        tiles, grid_count = read_tiles(path, name)
        assert grid_count == count == solid.voxel_count
        assert sorted(tiles) == sorted(density_tiles)
    colour_tiles, _ = read_tiles(path, "color")
    for value in colour_tiles.values():
        np.testing.assert_allclose(value, (0.3, 0.6, 0.1), atol=1e-6)
    assert solid.stats["solid"]["attribute_fallback"] == 0


def test_open_cube_inside_follows_the_rule_too(tmp_path):
    # A cube without one face (winding number): the inside's boundary there is no surface.
    v = np.array([(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)], np.float32)
    t = np.array(
        [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1), (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4)],
        np.uint32,
    )  # x = 1 face removed
    colors = np.random.default_rng(3).random((8, 3)).astype(np.float32)
    solid, tiles, _ = check_solid_attributes(v, t, tmp_path, method="cpu", resolution=48, colors=colors)
    assert solid.stats["solid"]["inside_rule"] == "winding"
    assert tiles


def test_inside_values_over_the_memory_budget_are_refused(spot_vcolor):
    # The inside's values (every leaf voxel's channels) are counted before they are allocated.
    v, t, colors = spot_vcolor
    kw = dict(resolution=400, mode="solid", colors=colors, attributes="color,normal")
    with pytest.raises(hyvox.ResourceError, match="inside's attribute values need about"):
        hyvox.voxelize(v, t, memory_budget_mib=100, **kw)
    assert hyvox.voxelize(v, t, memory_budget_mib=100, resolution=400, mode="solid").voxel_count > 0
