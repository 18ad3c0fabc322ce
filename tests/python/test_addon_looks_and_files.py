# SPDX-License-Identifier: GPL-3.0-or-later
"""bpy-free pieces of how a volume looks and which files it keeps: the material's density
from a run's stats (core/volume_look.py) at two resolutions of the same mesh, the module's
messages in the add-on's words (core/messages.py), and Clean Unused Files keeping a result's
.vox with its .vdb and the files undo can reach (core/cleanup.py)."""

import os
import sys

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "addon"))

from hyvox_blender.core import cleanup, messages, naming, volume_look  # noqa: E402
from hyvox_blender.core.errors import HyvoxError  # noqa: E402


@pytest.fixture(scope="module")
def bunny(mesh_dir):
    import hyvox

    return hyvox.read_mesh(str(mesh_dir / "bunny_stanford_69k.ply"))


def density(grid):
    return volume_look.result_density(dict(grid.stats), grid.voxel_size, grid.dims)


def test_solid_density_is_per_world_unit_and_a_shell_per_voxel_layer(bunny):
    import hyvox

    runs = {
        (mode, res, padding): hyvox.voxelize(*bunny, resolution=res, mode=mode, padding=padding)
        for mode in ("solid", "conservative")
        for res in (48, 256)
        for padding in (0, 3)
    }
    longest = float((bunny[0].max(axis=0) - bunny[0].min(axis=0)).max())
    for res in (48, 256):
        for padding in (0, 3):
            # Filled: SOLID_MEAN_FREE_PATHS across the mesh's longest side, whatever the resolution.
            assert density(runs["solid", res, padding]) == pytest.approx(
                volume_look.SOLID_MEAN_FREE_PATHS / longest, rel=1e-6
            )
            # A shell: the same optical depth per voxel layer.
            grid = runs["conservative", res, padding]
            assert density(grid) * grid.voxel_size == pytest.approx(volume_look.SHELL_DEPTH_PER_LAYER)


def test_memory_budget_messages_name_the_preference():
    where = "Preferences \u25b8 Memory Budget"
    for native in (
        "a 8192x8192x8192 grid needs about 38126 MiB (its bits and about 4 leaves of surface), more "
        "than the memory budget of 16 MiB; use a larger voxel size",
        "the OpenVDB grid of 9 leaves needs about 20 MiB, more than the memory budget of 16 MiB; "
        "raise the budget (memory_budget_mib) or use a larger voxel size",
    ):
        text = str(HyvoxError("cpu: " + native))
        assert text.count(where) == 1 and "memory_budget_mib" not in text, text
        assert messages.in_addon_words(text) == text  # said once
    assert str(HyvoxError("nothing to voxelize")) == "nothing to voxelize"


def test_clean_keeps_a_results_vox_and_what_undo_reaches(tmp_path):
    def make(name):
        path = tmp_path / name
        path.write_bytes(b"x")
        return str(path)

    used = make("Cube_voxels_r000001x.vdb")
    used_vox = make("Cube_voxels_r000001x.vox")
    frames = [make(f"Ball_voxels_r000002x_{n:04d}.vdb") for n in (1, 2)]
    frame_vox = [make(f"Ball_voxels_r000002x_{n:04d}.vox") for n in (1, 2)]
    undone = make("Cube_voxels_r000003x.vdb")  # a run undo can bring back
    undone_vox = make("Cube_voxels_r000003x.vox")
    replaced = [make("Cube_voxels_r000004x.vdb"), make("Cube_voxels_r000004x.vox")]
    keep = {cleanup.file_key(undone), cleanup.file_key(undone_vox)}
    unused = cleanup.unused_files([str(tmp_path)], [used], [frames[0]], naming.is_voxel_file, keep)
    assert unused == sorted(replaced)
    unused = cleanup.unused_files([str(tmp_path)], [used], [frames[0]], naming.is_voxel_file)
    assert unused == sorted(replaced + [undone, undone_vox])
    assert set(frame_vox + [used_vox]).isdisjoint(unused)
