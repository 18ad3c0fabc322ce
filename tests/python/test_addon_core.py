# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's bpy-free layer: settings, naming, alignment math, mesh merging."""
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "addon"))

from hyvox_blender.core import alignment, naming  # noqa: E402
from hyvox_blender.core.errors import SettingsError  # noqa: E402
from hyvox_blender.core.pipeline import merge_meshes  # noqa: E402
from hyvox_blender.core.settings import VoxelizeSettings, parse_frame_range  # noqa: E402


def test_core_never_imports_bpy():
    assert "bpy" not in sys.modules


@pytest.mark.parametrize("bad", [
    dict(method="magic"), dict(mode="thick"), dict(resolution=0), dict(resolution=100000),
    dict(voxel_size=-1.0), dict(tess_gamma=0.0), dict(padding=-1),
    dict(frames=[]), dict(frames=[-2, -1]), dict(memory_budget_mib=0),
])
def test_settings_rejected(bad):
    with pytest.raises(SettingsError):
        VoxelizeSettings(**bad).validate()


def test_settings_voxel_size_wins_over_resolution():
    settings = VoxelizeSettings(resolution=0, voxel_size=0.1).validate()
    assert settings.voxelize_options() == {"voxel_size": 0.1}
    assert not settings.is_sequence
    assert VoxelizeSettings(frames=[1, 2]).is_sequence


@pytest.mark.parametrize("text,frames", [
    ("7", [7]), ("1-4", [1, 2, 3, 4]), ("0-6:3", [0, 3, 6]), (" 10-12 ", [10, 11, 12]),
])
def test_frame_ranges(text, frames):
    assert parse_frame_range(text) == frames


@pytest.mark.parametrize("text", ["", "a-b", "5-1", "1-4:0"])
def test_bad_frame_ranges(text):
    with pytest.raises(SettingsError):
        parse_frame_range(text)


def test_file_names():
    assert naming.volume_file_name("Suzanne") == "Suzanne_voxels.vdb"
    assert naming.volume_file_name("Suzanne", 1) == "Suzanne_voxels_0001.vdb"
    assert naming.volume_file_name("Suzanne", 12345) == "Suzanne_voxels_12345.vdb"
    # Unsafe characters and trailing digits (Blender would read them as a frame number).
    assert naming.volume_file_name("a/b:c*") == "a_b_c_voxels.vdb"
    # One plain object keeps its name; groups and names a file cannot hold get a hash of
    # their sources, so two different results never share a file.
    assert naming.result_stem("Cube.001", "Cube.001", 1) == "Cube.001"
    ab = naming.result_stem("A_and_1_more", naming.group_key(["A", "B"]), 2)
    ac = naming.result_stem("A_and_1_more", naming.group_key(["A", "C"]), 2)
    assert ab.startswith("A_and_1_more_") and ac.startswith("A_and_1_more_") and ab != ac
    assert naming.result_stem("a/b", "a/b", 1) != naming.result_stem("a_b", "a_b", 1) == "a_b"
    assert naming.object_name("Bunny") == "Bunny_voxels"


def test_staging_is_hidden_sibling(tmp_path):
    final = str(tmp_path / "x.vdb")
    staging = naming.staging_path(final)
    assert os.path.dirname(staging) == str(tmp_path)
    assert os.path.basename(staging).startswith(".x.vdb.")


def test_groups_and_keys():
    assert naming.group_name(["A"], None) == "A"
    assert naming.group_name(["B", "A"], "B") == "B_and_1_more"
    assert naming.group_name(["B", "A"], None) == "A_and_1_more"
    assert naming.group_key(["B", "A"]) == naming.group_key(["A", "B"])


def test_default_output_dir(tmp_path):
    blend = str(tmp_path / "shot.blend")
    assert naming.default_output_dir(blend) == str(tmp_path / "hyvox_cache" / "shot")
    assert naming.default_output_dir("").endswith(os.path.join("hyvox_cache", "unsaved"))


def test_half_voxel_shift_by_version():
    assert alignment.needs_half_voxel_shift((3, 4, 1))
    assert not alignment.needs_half_voxel_shift(alignment.FIRST_CENTRED_VERSION)
    assert alignment.needs_half_voxel_shift((9, 0, 0), "ON")
    assert not alignment.needs_half_voxel_shift((3, 4, 1), "OFF")
    assert alignment.object_offset(0.5, (3, 4, 1)) == (-0.25, -0.25, -0.25)
    assert alignment.needs_half_voxel_shift((4, 2, 0))
    assert alignment.object_offset(0.5, (5, 0, 0)) == (0.0, 0.0, 0.0)


def test_merge_meshes_offsets_indices():
    a = (np.zeros((3, 3), np.float32), np.array([[0, 1, 2]], np.uint32))
    b = (np.ones((4, 3), np.float32), np.array([[0, 1, 2], [1, 2, 3]], np.uint32))
    vertices, triangles = merge_meshes([a, b])
    assert vertices.shape == (7, 3) and vertices.dtype == np.float32
    assert triangles.dtype == np.uint32
    np.testing.assert_array_equal(triangles, [[0, 1, 2], [3, 4, 5], [4, 5, 6]])
