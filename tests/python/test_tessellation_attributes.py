# SPDX-License-Identifier: GPL-3.0-or-later
# Attribute voxels of the tessellation method: the mean of the values of the points that land
# in each voxel (section 3.2's multi-valued voxels). Checked against the exact cpu values
# (themselves checked against the numpy oracle in test_attributes.py), against constants a
# mean must reproduce, and against the known normals of a sphere and a cube.
import numpy as np
import pytest

import hyvox
from attribute_oracle import srgb_to_linear

GAMMAS = (1, 2, 4)


def by_voxel(ijk, dims):
    ijk = np.asarray(ijk, dtype=np.int64)
    return (ijk[:, 0] * dims[1] + ijk[:, 1]) * dims[2] + ijk[:, 2]


def same_voxels_as_density(grid, plain):
    """Every attribute row belongs to exactly one of the density grid's voxels, and asking
    for attributes does not change the voxels (plain: the same run without attributes)."""
    assert np.array_equal(grid.coords(), plain.coords())
    assert grid.stats["attribute_voxels_unreached"] == 0
    for values in grid.attributes().values():
        assert values.shape[0] == grid.voxel_count == len(grid.coords())


def mean_errors(grid, exact, names):
    """Mean absolute error per attribute against the exact grid, on the voxels both have."""
    keys, exact_keys = by_voxel(grid.coords(), grid.dims), by_voxel(exact.coords(), exact.dims)
    common, mine, theirs = np.intersect1d(keys, exact_keys, return_indices=True)
    assert len(common) > 0.85 * len(exact_keys)  # the tessellation's voxels are nearly all of them
    return {n: float(np.abs(grid.attributes()[n][mine] - exact.attributes()[n][theirs]).mean()) for n in names}


@pytest.fixture(scope="module")
def spot_vcolor(mesh_dir):
    v, t, attrs = hyvox.read_mesh(mesh_dir / "spot_vcolor.ply", attributes=True)
    return v, t, srgb_to_linear(attrs["colors"][:, :3]).astype(np.float32)


# Bounds: the largest mean errors at gamma 1 measured on llvmpipe (resolution 32: colour
# 0.0087, normal 0.0136), doubled.
@pytest.mark.parametrize("resolution", [32, 64])
def test_vertex_colours_approach_the_exact_values_as_gamma_grows(spot_vcolor, resolution):
    v, t, colors = spot_vcolor
    exact = hyvox.voxelize(v, t, resolution=resolution, method="cpu", colors=colors, attributes="color,normal")
    errors = []
    for gamma in GAMMAS:
        options = dict(resolution=resolution, method="tessellation", tess_gamma=gamma)
        grid = hyvox.voxelize(v, t, colors=colors, attributes="color,normal", **options)
        same_voxels_as_density(grid, hyvox.voxelize(v, t, **options))
        errors.append(mean_errors(grid, exact, ("color", "normal")))
    assert errors[0]["color"] < 0.02 and errors[0]["normal"] < 0.03, errors
    for name in ("color", "normal"):
        series = [e[name] for e in errors]
        assert all(b <= a for a, b in zip(series, series[1:])), (name, series)
    # Not flat: a wrong interpolation would show.
    assert grid.attributes()["color"].std(axis=0).min() > 0.05


def test_texture_approaches_the_exact_values_as_gamma_grows(mesh_dir):
    v, t, attrs = hyvox.read_mesh(mesh_dir / "spot_uv.ply", attributes=True)
    sources = dict(uvs=attrs["uvs"], texture=mesh_dir / "spot_texture.png")
    exact = hyvox.voxelize(v, t, resolution=64, method="cpu", attributes="color", **sources)
    errors = []
    for gamma in GAMMAS:
        options = dict(resolution=64, method="tessellation", tess_gamma=gamma)
        grid = hyvox.voxelize(v, t, attributes="color", **sources, **options)
        same_voxels_as_density(grid, hyvox.voxelize(v, t, **options))
        errors.append(mean_errors(grid, exact, ("color",))["color"])
    assert errors[0] < 0.015, errors  # measured at gamma 1 on llvmpipe: 0.0071
    assert all(b <= a for a, b in zip(errors, errors[1:])), errors
    assert grid.attributes()["color"].std(axis=0).min() > 0.05


@pytest.mark.parametrize("source", ["vertex", "corner", "palette"])
def test_a_constant_colour_is_reproduced_everywhere(spot_vcolor, source):
    v, t, _ = spot_vcolor
    rgba = np.array([0.25, 0.5, 0.75, 0.125], np.float32)
    sources = {
        "vertex": dict(colors=np.tile(rgba[:3], (len(v), 1))),
        "corner": dict(colors=np.tile(rgba, (3 * len(t), 1))),
        "palette": dict(material_ids=np.ones(len(t), np.uint32), palette=np.array([[1, 0, 0, 1], rgba])),
    }[source]
    grid = hyvox.voxelize(v, t, resolution=48, method="tessellation", tess_gamma=2, attributes="color", **sources)
    got = grid.attributes()
    assert got["color"].shape == (grid.voxel_count, 3)
    # Up to the fixed point of the sums (2^-18 per point) and float barycentrics.
    np.testing.assert_allclose(got["color"], np.broadcast_to(rgba[:3], got["color"].shape), rtol=0, atol=1e-5)
    if source != "vertex":
        np.testing.assert_allclose(got["alpha"], rgba[3], rtol=0, atol=1e-5)


def uv_sphere(rings=24, segments=48):
    """Unit sphere, outward-wound, with its exact vertex normals (= positions)."""
    theta = np.linspace(0, np.pi, rings + 1)[1:-1]
    phi = np.linspace(0, 2 * np.pi, segments, endpoint=False)
    ring = np.stack(
        [
            np.outer(np.sin(theta), np.cos(phi)),
            np.outer(np.sin(theta), np.sin(phi)),
            np.repeat(np.cos(theta)[:, None], segments, 1),
        ],
        axis=-1,
    ).reshape(-1, 3)
    v = np.vstack([[0, 0, 1], ring, [0, 0, -1]])
    at = lambda r, s: 1 + r * segments + s % segments  # noqa: E731
    tris = [[0, at(0, s), at(0, s + 1)] for s in range(segments)]
    for r in range(rings - 2):
        for s in range(segments):
            tris += [[at(r, s), at(r + 1, s), at(r + 1, s + 1)], [at(r, s), at(r + 1, s + 1), at(r, s + 1)]]
    bottom = len(v) - 1
    tris += [[bottom, at(rings - 2, s + 1), at(rings - 2, s)] for s in range(segments)]
    return v.astype(np.float32), np.array(tris, np.uint32)


@pytest.mark.parametrize("given_normals", [True, False])
def test_sphere_normals_point_outwards(given_normals):
    v, t = uv_sphere()
    extra = dict(normals=v) if given_normals else {}
    grid = hyvox.voxelize(v, t, resolution=40, method="tessellation", tess_gamma=2, attributes="normal", **extra)
    n = grid.attributes()["normal"]
    centres = grid.origin + (grid.coords() + 0.5) * grid.voxel_size
    outward = centres / np.linalg.norm(centres, axis=1, keepdims=True)
    np.testing.assert_allclose(np.linalg.norm(n, axis=1), 1, atol=1e-5)
    # A voxel's centre is at most half a diagonal (0.87 voxel) off the surface, ~20 voxels out.
    assert (np.einsum("ij,ij->i", n, outward) > 0.95).all()


def test_cube_normals_are_its_face_normals():
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], np.float32)
    faces = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]  # -x +x -y +y -z +z
    t = np.array([[a, b, c] for a, b, c, d in faces] + [[a, c, d] for a, b, c, d in faces], np.uint32)
    grid = hyvox.voxelize(corners, t, voxel_size=0.1, method="tessellation", attributes="normal")
    n = grid.attributes()["normal"]
    centres = grid.origin + (grid.coords() + 0.5) * grid.voxel_size
    assert (np.einsum("ij,ij->i", n, centres) > 0).all()  # outwards, edges and corners included
    # Away from the edges a voxel sees one face: its normal is that face's axis.
    inner = (np.abs(centres) < 0.85).sum(axis=1) == 2
    assert inner.sum() > 0.5 * len(centres)
    axis = np.argmax(np.abs(centres), axis=1)
    expected = np.zeros_like(n)
    expected[np.arange(len(n)), axis] = np.sign(centres[np.arange(len(n)), axis])
    np.testing.assert_allclose(n[inner], expected[inner], atol=1e-6)


def test_values_are_the_same_on_every_run_and_tiling(spot_vcolor):
    # Integer sums commute: neither the order the GPU runs the points in nor the tiling
    # (each tile draws its own points of the same triangles) changes a bit.
    v, t, colors = spot_vcolor
    whole, again, tiled = (
        hyvox.voxelize(
            v,
            t,
            resolution=48,
            method="tessellation",
            tess_gamma=2,
            tile_size=size,
            colors=colors,
            attributes="color,normal",
        )
        for size in (0, 0, 16)
    )
    assert whole.stats["tiles"] == 1 and tiled.stats["tiles"] > 1
    for other in (again, tiled):
        assert np.array_equal(whole.coords(), other.coords())
        for name in ("color", "normal"):
            assert np.array_equal(whole.attributes()[name], other.attributes()[name])


def test_tiles_keep_the_sums_within_the_budget(spot_vcolor):
    # Automatic tiles are small enough for every brick's sums; a tile_size asked for that is
    # too large for them is a clear error.
    v, t, colors = spot_vcolor
    options = dict(resolution=64, method="tessellation", colors=colors, attributes="color,normal")
    with pytest.raises(hyvox.ResourceError, match="attribute sums need .* lower tile_size"):
        hyvox.voxelize(v, t, memory_budget_mib=1, tile_size=64, **options)
    small, roomy = (hyvox.voxelize(v, t, memory_budget_mib=mib, **options) for mib in (1, 4096))
    assert small.stats["tiles"] > 1 and roomy.stats["tiles"] == 1
    assert np.array_equal(small.coords(), roomy.coords())
    for name in ("color", "normal"):
        assert np.array_equal(small.attributes()[name], roomy.attributes()[name])
