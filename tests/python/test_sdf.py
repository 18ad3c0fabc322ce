# SPDX-License-Identifier: GPL-3.0-or-later
"""The sdf attribute (docs/sdf.md) against numpy and OpenVDB: its distances against a
brute-force numpy closest point (Ericson's, in double) on sampled band voxels, its signs
against the same run's solid voxels, the .vdb's level set read back by pyopenvdb (class,
background, transform, values) and meshed by OpenVDB (watertight, on the source), the
front doors' spellings, every method and mode giving the same sdf, and Sponza's inside kept
where OpenVDB's own level set (its flood fill, what Blender's Mesh to SDF Grid runs) loses it."""

import subprocess

import numpy as np
import pytest

import hyvox

vdb = pytest.importorskip("pyopenvdb")


def closest_distance(points, a, b, c):
    """Distances (P,) from points (P, 3) to the nearest of triangles a, b, c (T, 3) each:
    Ericson's Voronoi regions of each triangle, every point against every triangle, float64."""
    out = np.empty(len(points))
    step = max(1, 400_000 // len(a))  # points at a time: about 400k point-triangle pairs
    for first in range(0, len(points), step):
        out[first : first + step] = _closest_distance(points[first : first + step], a, b, c)
    return out


def _closest_distance(points, a, b, c):
    best = np.full(len(points), np.inf)
    for start in range(0, len(a), 400_000):
        A, B, C = a[start : start + 400_000], b[start : start + 400_000], c[start : start + 400_000]
        p = points[:, None, :]
        ab, ac, ap = B - A, C - A, p - A
        d1, d2 = np.einsum("tk,ptk->pt", ab, ap), np.einsum("tk,ptk->pt", ac, ap)
        bp = p - B
        d3, d4 = np.einsum("tk,ptk->pt", ab, bp), np.einsum("tk,ptk->pt", ac, bp)
        cp = p - C
        d5, d6 = np.einsum("tk,ptk->pt", ab, cp), np.einsum("tk,ptk->pt", ac, cp)
        va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
        with np.errstate(divide="ignore", invalid="ignore"):
            denom = 1.0 / (va + vb + vc)
            v, w = vb * denom, vc * denom
            q = A + ab * v[..., None] + ac * w[..., None]  # inside the face
            regions = [
                (d1 <= 0) & (d2 <= 0),
                (d3 >= 0) & (d4 <= d3),
                (vc <= 0) & (d1 >= 0) & (d3 <= 0),
                (d6 >= 0) & (d5 <= d6),
                (vb <= 0) & (d2 >= 0) & (d6 <= 0),
                (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0),
            ]
            targets = [
                np.broadcast_to(A, q.shape),
                np.broadcast_to(B, q.shape),
                A + ab * (d1 / (d1 - d3))[..., None],
                np.broadcast_to(C, q.shape),
                A + ac * (d2 / (d2 - d6))[..., None],
                B + (C - B) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))[..., None],
            ]
        done = np.zeros(d1.shape, bool)
        for region, target in zip(regions, targets):  # the first region that holds, as Ericson tests them
            take = region & ~done
            q = np.where(take[..., None], target, q)
            done |= region
        best = np.minimum(best, np.linalg.norm(p - q, axis=2).min(axis=1))
    return best


def triangles_of(vertices, triangles):
    v = np.asarray(vertices, np.float64)
    t = np.asarray(triangles)
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    keep = np.linalg.norm(np.cross(b - a, c - a), axis=1) > 0  # the usable ones
    return a[keep], b[keep], c[keep]


def centres(grid, ijk):
    return np.asarray(grid.origin) + (np.asarray(ijk, np.float64) + 0.5) * grid.voxel_size


@pytest.mark.parametrize("name", ["spot", "elephant"])
def test_band_distances_match_numpy_brute_force(name, spot, elephant):
    vertices, triangles = {"spot": spot, "elephant": elephant}[name]
    grid = hyvox.voxelize(vertices, triangles, resolution=40, mode="solid", attributes=("sdf",))
    ijk, distance = grid.sdf()
    s = grid.voxel_size
    assert len(ijk) == grid.stats["sdf"]["active_voxels"] > 1000
    assert np.all(np.abs(distance) < 3 * s)
    rng = np.random.default_rng(4)
    sample = rng.choice(len(ijk), 200, replace=False)
    exact = closest_distance(centres(grid, ijk[sample]), *triangles_of(vertices, triangles))
    np.testing.assert_array_less(np.abs(np.abs(distance[sample].astype(np.float64)) - exact) / s, 1e-5)


@pytest.mark.parametrize("name", ["spot", "elephant"])
def test_signs_are_the_solid_runs_inside(name, spot, elephant):
    # Off the surface, the same run's solid voxels are exactly the negative ones.
    vertices, triangles = {"spot": spot, "elephant": elephant}[name]
    solid = hyvox.voxelize(vertices, triangles, resolution=40, mode="solid", attributes="sdf")
    surface = hyvox.voxelize(vertices, triangles, resolution=40, attributes="sdf")
    assert solid.dims == surface.dims
    ijk, distance = solid.sdf()
    occupied = np.zeros(solid.dims, bool)
    occupied[tuple(solid.coords().T)] = True
    on_surface = np.zeros(solid.dims, bool)
    on_surface[tuple(surface.coords().T)] = True
    off = ~on_surface[tuple(ijk.T)]
    inside = occupied[tuple(ijk.T)]
    assert off.sum() > 1000 and (inside & off).sum() > 100
    np.testing.assert_array_equal(distance[off] < 0, inside[off])
    # Conservative mode: the surface's voxels, the same sdf (its sign is the inside test).
    surface_ijk, surface_distance = surface.sdf()
    np.testing.assert_array_equal(surface_ijk, ijk)
    np.testing.assert_array_equal(surface_distance, distance)


def test_the_vdb_holds_an_openvdb_level_set(spot, tmp_path):
    vertices, triangles = spot
    grid = hyvox.voxelize(
        vertices,
        triangles,
        resolution=40,
        mode="solid",
        attributes=("color", "sdf"),
        colors=np.ones((len(vertices), 3)),
    )
    path = tmp_path / "spot.vdb"
    grid.write_vdb(path)
    grids = {g.name: g for g in vdb.readAll(str(path))[0]}
    assert set(grids) == {"density", "color", "sdf"}
    sdf, density = grids["sdf"], grids["density"]
    s = grid.voxel_size
    assert sdf.gridClass == vdb.GridClass.LEVEL_SET
    assert sdf.background == pytest.approx(3 * s, rel=1e-6)
    assert grid.stats["sdf"]["background"] == pytest.approx(3 * s, rel=1e-6)
    for index in [(0, 0, 0), (7, -3, 11)]:  # the same transform as density's
        np.testing.assert_allclose(sdf.transform.indexToWorld(index), density.transform.indexToWorld(index))
    ijk, distance = grid.sdf()
    assert sdf.activeVoxelCount() == len(ijk)
    accessor = sdf.getConstAccessor()
    for n in range(0, len(ijk), 97):
        value, active = accessor.probeValue(tuple(int(x) for x in ijk[n]))
        assert active and value == distance[n]
    # The inside beyond the band: inactive, -background; outside, +background.
    occupied = np.zeros(grid.dims, bool)
    occupied[tuple(grid.coords().T)] = True
    band = np.zeros(grid.dims, bool)
    band[tuple(ijk.T)] = True
    deep = np.argwhere(occupied & ~band)
    far = np.argwhere(~occupied & ~band)
    assert len(deep) > 100 and len(far) > 100
    for ijk_deep in deep[::37]:
        assert accessor.probeValue(tuple(int(x) for x in ijk_deep)) == (-sdf.background, False)
    for ijk_far in far[::101]:
        assert accessor.probeValue(tuple(int(x) for x in ijk_far)) == (sdf.background, False)


def test_openvdb_meshes_it_watertight_on_the_source(spot, tmp_path):
    vertices, triangles = spot
    grid = hyvox.voxelize(vertices, triangles, resolution=48, mode="solid", attributes="sdf")
    path = tmp_path / "spot.vdb"
    grid.write_vdb(path)
    sdf = vdb.read(str(path), "sdf")
    points, tris, quads = sdf.convertToPolygons(0.0, 0.0)  # volumeToMesh, as Grid to Mesh runs it
    assert len(quads) > 1000
    edges = np.concatenate(
        [quads[:, [k, (k + 1) % 4]] for k in range(4)] + [tris[:, [k, (k + 1) % 3]] for k in range(3)]
    )
    _, uses = np.unique(np.sort(edges, axis=1), axis=0, return_counts=True)
    assert np.all(uses == 2)  # closed
    off = closest_distance(np.asarray(points[::20], np.float64), *triangles_of(vertices, triangles)) / grid.voxel_size
    assert np.median(off) < 0.05 and off.max() < 0.5


def test_band_option_and_padding_from_the_cli(cli, mesh_dir, tmp_path):
    out = tmp_path / "spot.vdb"
    done = subprocess.run(
        [
            str(cli),
            "voxelize",
            str(mesh_dir / "spot_vcolor.ply"),
            "-o",
            str(out),
            "--resolution",
            "32",
            "--attributes",
            "sdf",
            "--sdf-band",
            "2",
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    v, t = hyvox.read_mesh(mesh_dir / "spot_vcolor.ply")
    plain = hyvox.voxelize(v, t, resolution=32)
    python = hyvox.voxelize(v, t, resolution=32, attributes=["sdf"], sdf_band=2)
    assert python.dims == tuple(d + 4 for d in plain.dims)  # padded by the band on every side
    sdf = vdb.read(str(out), "sdf")
    assert sdf.background == pytest.approx(2 * python.voxel_size, rel=1e-6)
    ijk, distance = python.sdf()
    assert sdf.activeVoxelCount() == len(ijk)
    assert np.all(np.abs(distance) < 2 * python.voxel_size)
    for bad in (0, 65):
        with pytest.raises(ValueError, match="sdf_band must be a whole number between 1 and 64"):
            hyvox.voxelize(v, t, resolution=8, attributes="sdf", sdf_band=bad)


def test_every_method_and_mode_gives_the_same_sdf(spot):
    # The sign is the inside test on the exact conservative surface, the distances the mesh's:
    # what a method or mode draws as the density does not change them.
    vertices, triangles = spot
    reference = hyvox.voxelize(vertices, triangles, resolution=20, mode="solid", method="cpu", attributes="sdf")
    ijk, distance = reference.sdf()
    for method in hyvox.METHODS:
        for mode in ("conservative", "thin", "solid"):
            grid = hyvox.voxelize(vertices, triangles, resolution=20, mode=mode, method=method, attributes="sdf")
            got_ijk, got = grid.sdf()
            np.testing.assert_array_equal(got_ijk, ijk, err_msg=f"{method} {mode}")
            np.testing.assert_array_equal(got, distance, err_msg=f"{method} {mode}")
    assert hyvox.voxelize(vertices, triangles, resolution=20).sdf() is None


def winding_numbers(points, a, b, c):
    """The exact generalized winding number (every triangle's solid angle, van Oosterom and
    Strackee) at each point, float64."""
    out = np.zeros(len(points))
    for n, p in enumerate(points):
        x, y, z = a - p, b - p, c - p
        lx, ly, lz = (np.linalg.norm(v, axis=1) for v in (x, y, z))
        det = np.einsum("ij,ij->i", x, np.cross(y, z))
        div = (
            lx * ly * lz
            + np.einsum("ij,ij->i", x, y) * lz
            + np.einsum("ij,ij->i", y, z) * lx
            + np.einsum("ij,ij->i", z, x) * ly
        )
        out[n] = np.arctan2(det, div).sum() / (2 * np.pi)
    return out


def test_sponza_keeps_its_inside_where_openvdb_level_set_loses_it(mesh_dir):
    # Sponza is open (25k boundary edges). OpenVDB's meshToLevelSet (pyopenvdb's
    # createLevelSetFromPolygons, what Blender's Mesh to SDF Grid node runs) on the same
    # transform and band: voxels whose signs differ, counted; on a sample of them the exact
    # winding number agrees with hyvox wherever it is clear of 0.5.
    vertices, triangles = hyvox.read_mesh(mesh_dir / "sponza_crytek_262k_vcolor.ply.gz")
    grid = hyvox.voxelize(vertices, triangles, resolution=64, mode="solid", attributes="sdf")
    s = grid.voxel_size
    transform = vdb.createLinearTransform(s)
    transform.translate(tuple(float(o + s / 2) for o in grid.origin))  # index (i, j, k): voxel (i, j, k)'s centre
    theirs = vdb.FloatGrid.createLevelSetFromPolygons(
        np.asarray(vertices, np.float32), triangles=np.asarray(triangles, np.int32), transform=transform, halfWidth=3.0
    )
    ijk, distance = grid.sdf()
    dense = np.empty(grid.dims, np.float32)
    theirs.copyToArray(dense, ijk=(0, 0, 0))  # every voxel of the grid, its band's or ±background
    their_value = dense[tuple(ijk.T)]
    in_their_band = np.abs(their_value) < theirs.background
    clear = np.abs(distance) > 0.05 * s
    differ = np.flatnonzero(in_their_band & clear & ((distance < 0) != (their_value < 0)))
    assert len(differ) > 2000, len(differ)
    sample = np.random.default_rng(7).choice(differ, 40, replace=False)
    w = winding_numbers(centres(grid, ijk[sample]), *triangles_of(vertices, triangles))
    decided = np.abs(w - 0.5) > 0.1
    assert decided.sum() > 25
    np.testing.assert_array_equal((distance[sample] < 0)[decided], (w >= 0.5)[decided])
