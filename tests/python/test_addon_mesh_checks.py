# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's checks of an object's vertices (core/mesh_checks.py): the first unusable
coordinate found as numpy finds it, and the far-vertex warning against meshes whose strays
are known (added by the test) and real meshes that have none."""

import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "addon"))

from hyvox_blender.core import mesh_checks  # noqa: E402

CUBE = np.array([(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], np.float32)


def test_first_bad_vertex_is_the_first_nan_inf_or_float_max():
    vertices = np.zeros((10, 3), np.float32)
    assert mesh_checks.first_bad_vertex(vertices) is None
    vertices[7, 0] = np.nan
    vertices[4, 2] = -np.finfo(np.float32).max  # how Blender stores -Inf
    assert mesh_checks.first_bad_vertex(vertices) == 4
    vertices[4, 2] = np.nextafter(np.float32(3.4e38), np.float32(0))  # a (huge) number
    assert mesh_checks.first_bad_vertex(vertices) == 7
    message = mesh_checks.bad_vertex_message("Cube", 4, np.float32([0, 0, np.finfo(np.float32).max]))
    assert message.startswith("Cube: vertex 4 is at (0, 0, 3.40282e+38)") and "Blender stores Inf" in message


def grid_points(n, extent=(2.0, 2.0, 2.0)):
    axes = [np.linspace(-e / 2, e / 2, n) for e in extent]
    return np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3)


@pytest.mark.parametrize("strays", [1, 2, 3])
def test_a_few_far_vertices_are_named(strays):
    far = np.array([(500.0, 0, 0), (0, -300.0, 0), (0, 0, 800.0)])[:strays]
    for mesh in (CUBE, grid_points(20)):
        warning = mesh_checks.far_vertices_warning("Cube", np.concatenate([mesh, far]))
        count = f"{strays} vertex{'es' if strays > 1 else ''} far from the rest"
        assert warning.startswith(f"Cube: {count}"), warning
        assert "spans 2 units" not in warning and "the rest of it 2)" in warning


def test_no_warning_without_strays(mesh_dir):
    import hyvox

    bunny, _ = hyvox.read_mesh(str(mesh_dir / "bunny_stanford_69k.ply"))
    for vertices in (
        CUBE,
        grid_points(20),
        grid_points(10, (1000.0, 1.0, 1.0)),
        bunny,
        np.concatenate([grid_points(10), grid_points(10) + (100.0, 0, 0)]),
    ):  # two equal parts
        assert mesh_checks.far_vertices_warning("Mesh", vertices) == ""


def test_more_than_a_few_far_vertices_are_a_part_not_strays():
    # A thousandth of the vertices, or at least 3: here 8 far vertices of 1008 are a small part.
    mesh = np.concatenate([grid_points(10), CUBE * 0.01 + (500.0, 0, 0)])
    assert len(mesh) == 1008
    assert mesh_checks.far_vertices_warning("Mesh", mesh) == ""


def test_used_vertices_leave_out_loose_ones():
    vertices = np.concatenate([CUBE, [(1e6, 0, 0)]])
    triangles = np.array([[0, 1, 2], [5, 6, 7]], np.uint32)
    np.testing.assert_array_equal(mesh_checks.used_vertices(vertices, triangles), CUBE[[0, 1, 2, 5, 6, 7]])


def fan(vertices):
    """Triangles using every vertex (a fan from vertex 0; the last ones repeat to fill)."""
    n = len(vertices)
    rest = np.arange(1, n - 1)
    return np.stack([np.zeros(len(rest), np.int64), rest, rest + 1], -1).astype(np.uint32)


def test_the_quick_object_check_answers_as_the_whole_check(mesh_dir):
    """object_far_vertices_warning (a bound first) gives exactly far_vertices_warning of the used
    vertices: on real meshes, meshes with strays, loose far vertices and objects of two parts."""
    import hyvox

    bunny, bunny_triangles = hyvox.read_mesh(str(mesh_dir / "bunny_stanford_69k.ply"))
    rng = np.random.default_rng(7)
    cases = [[(bunny, bunny_triangles)]]
    for strays in (1, 2, 3, 40, 200):  # a few, and more than a few, of 8,000
        points = np.concatenate([grid_points(20), rng.uniform(-1, 1, (strays, 3)) * 1e3])
        cases.append([(points, fan(points))])
    loose = np.concatenate([bunny, [(1e4, 0, 0)]])  # far, but no triangle uses it
    cases.append([(loose, bunny_triangles)])
    stray = np.concatenate([bunny, [(1e4, 0, 0)]])
    stray_triangles = np.concatenate([bunny_triangles, [[0, 1, len(bunny)]]]).astype(np.uint32)
    cases.append([(stray, stray_triangles)])
    cases.append([(bunny, bunny_triangles), (CUBE * 1e-3 + (40.0, 0, 0), fan(CUBE))])  # a far part of 8
    for _ in range(20):  # random clouds with random far points
        points = rng.normal(size=(int(rng.integers(50, 5000)), 3)) * rng.uniform(0.1, 10, 3)
        far = rng.normal(size=(int(rng.integers(0, 8)), 3)) * 10 ** rng.uniform(0, 4)
        points = np.concatenate([points, far])
        cases.append([(points, fan(points))])
    warned = 0
    for parts in cases:
        used = np.concatenate([mesh_checks.used_vertices(v, t) for v, t in parts])
        expected = mesh_checks.far_vertices_warning("Mesh", used)
        assert mesh_checks.object_far_vertices_warning("Mesh", parts) == expected
        warned += bool(expected)
    assert warned >= 5  # the cases include warnings, not only silences


def test_the_bound_never_exceeds_the_core(mesh_dir):
    import hyvox

    rng = np.random.default_rng(3)
    for name in ("bunny_stanford_69k.ply", "spot_vcolor.ply", "teapot_utah.ply"):
        vertices, triangles = hyvox.read_mesh(str(mesh_dir / name))
        used = mesh_checks.used_vertices(vertices, triangles).astype(np.float64)
        for few in (3, 10, int(rng.integers(11, 200))):
            # The core's longest side by brute force: per axis, the narrowest window of sorted
            # values that leaves out `few` of them, i below and few - i above.
            ordered = np.sort(used, axis=0)
            n = len(ordered)
            core = max(min(ordered[n - 1 - (few - i), a] - ordered[i, a] for i in range(few + 1)) for a in range(3))
            assert mesh_checks._core_side_lower_bound([(vertices, triangles)], few) <= core
