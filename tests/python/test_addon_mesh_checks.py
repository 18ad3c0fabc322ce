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
