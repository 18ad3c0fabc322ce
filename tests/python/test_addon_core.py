# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's bpy-free layer: settings, naming, alignment math, mesh merging."""

import os
import re
import subprocess
import sys
import tempfile

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "addon"))

from hyvox_blender.core import alignment, naming, session_folder  # noqa: E402
from hyvox_blender.core.errors import SettingsError  # noqa: E402
from hyvox_blender.core.pipeline import merge_meshes  # noqa: E402
from hyvox_blender.core.settings import VoxelizeSettings, parse_frame_range  # noqa: E402


def test_core_never_imports_bpy():
    assert "bpy" not in sys.modules


@pytest.mark.parametrize(
    "bad",
    [
        dict(method="magic"),
        dict(mode="thick"),
        dict(resolution=0),
        dict(resolution=100000),
        dict(voxel_size=-1.0),
        dict(tess_gamma=0.0),
        dict(padding=-1),
        dict(frames=[]),
        dict(frames=[-2, -1]),
        dict(memory_budget_mib=-1),
    ],
)
def test_settings_rejected(bad):
    with pytest.raises(SettingsError):
        VoxelizeSettings(**bad).validate()


def test_settings_pass_both_sizes_and_the_module_lets_voxel_size_win():
    from hyvox_blender.core import backend

    settings = VoxelizeSettings(resolution=8, voxel_size=0.1).validate()
    assert settings.options == {"resolution": 8, "voxel_size": 0.1}  # no rule of its own
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32)
    t = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], np.uint32)
    grid = backend.voxelize(backend.load_module(), v, t, settings, "cpu")
    assert grid.voxel_size == 0.1 and tuple(grid.dims) == (10, 10, 10)
    assert not settings.is_sequence
    assert VoxelizeSettings(frames=[1, 2]).is_sequence


@pytest.mark.parametrize(
    "text,frames",
    [
        ("7", [7]),
        ("1-4", [1, 2, 3, 4]),
        ("0-6:3", [0, 3, 6]),
        (" 10-12 ", [10, 11, 12]),
    ],
)
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
    # One plain object keeps its name; names a file cannot hold get a hash of their sources,
    # and so do groups under fixed names, so two different results never share a file.
    for fixed in (False, True):
        assert naming.result_stem("Cube.001", "Cube.001", 1, fixed) == "Cube.001"
        assert naming.result_stem("a/b", "a/b", 1, fixed) != naming.result_stem("a_b", "a_b", 1, fixed) == "a_b"
    ab = naming.result_stem("A_and_1_more", naming.group_key(["A", "B"]), 2, fixed_names=True)
    ac = naming.result_stem("A_and_1_more", naming.group_key(["A", "C"]), 2, fixed_names=True)
    assert ab.startswith("A_and_1_more_") and ac.startswith("A_and_1_more_") and ab != ac
    # With new names per run (a run tag) a group's files are named as its volume is.
    assert naming.result_stem("A_and_1_more", naming.group_key(["A", "B"]), 2) == "A_and_1_more"
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
    unsaved = naming.default_output_dir("")
    assert os.path.isdir(unsaved) and naming.default_output_dir("") == unsaved  # one per session
    assert os.path.dirname(unsaved) == tempfile.gettempdir()
    assert os.listdir(unsaved) == [session_folder.OWNER_FILE]  # which process made it


def test_unsaved_folder_is_unique_per_session():
    """Another session (another interpreter) gets another folder."""
    script = "from hyvox_blender.core import naming; print(naming.default_output_dir(''))"
    root = os.path.join(os.path.dirname(__file__), "..", "..", "addon")
    others = {
        subprocess.run(
            [sys.executable, "-c", script],
            capture_output=True,
            text=True,
            check=True,
            env=dict(os.environ, PYTHONPATH=root + os.pathsep + os.environ.get("PYTHONPATH", "")),
        ).stdout.strip()
        for _ in range(2)
    }
    assert len(others) == 2 and naming.default_output_dir("") not in others
    for folder in others:
        assert os.path.isdir(folder)
        assert session_folder.remove_if_empty(folder)


def test_run_tags_make_new_file_names_that_stay_sequences():
    tags = {naming.new_run_tag() for _ in range(200)}
    assert len(tags) == 200
    tag = tags.pop()
    single, frame = naming.volume_file_name("Cube", None, tag), naming.volume_file_name("Cube", 7, tag)
    assert single == f"Cube_voxels_{tag}.vdb" and frame == f"Cube_voxels_{tag}_0007.vdb"
    # Blender reads a sequence's frame from the last run of digits: it must be the frame.
    assert re.search(r"(\d+)\.vdb$", frame).group(1) == "0007" and not re.search(r"\d\.vdb$", single)
    for name in (single, frame, "Cube_voxels.vdb", "A_and_1_more_0badf00d_voxels_0001.vdb"):
        assert naming.is_voxel_file(name), name
    for name in ("notes.txt", "Cube.vdb", ".Cube_voxels.vdb.123.partial", "Cube_voxels.vdb.bak"):
        assert not naming.is_voxel_file(name), name


def test_half_voxel_shift_by_version():
    assert alignment.needs_half_voxel_shift((3, 4, 1))
    assert not alignment.needs_half_voxel_shift(alignment.FIRST_CENTRED_VERSION)
    assert alignment.needs_half_voxel_shift((9, 0, 0), "ON")
    assert not alignment.needs_half_voxel_shift((3, 4, 1), "OFF")
    assert alignment.object_offset(0.5, (3, 4, 1)) == (-0.25, -0.25, -0.25)
    assert alignment.needs_half_voxel_shift((4, 2, 0))
    assert alignment.object_offset(0.5, (5, 0, 0)) == (0.0, 0.0, 0.0)


def test_eevee_bounds_rule_covers_eevee_next_before_5():
    # EEVEE Next (4.2-4.5) clips the last voxel layer; legacy EEVEE (3.4) and 5.0 do not
    # (tests/blender/test_render_alignment.py renders it in 3.4.1, 4.5.15 and 5.0.1).
    assert [
        alignment.eevee_clips_last_voxel_layer(v)
        for v in [(3, 4, 1), (4, 1, 1), (4, 2, 0), (4, 5, 15), (5, 0, 0), (5, 0, 1)]
    ] == [False, False, True, True, False, False]


def test_merge_meshes_offsets_indices():
    a = (np.zeros((3, 3), np.float32), np.array([[0, 1, 2]], np.uint32))
    b = (np.ones((4, 3), np.float32), np.array([[0, 1, 2], [1, 2, 3]], np.uint32))
    vertices, triangles = merge_meshes([a, b])
    assert vertices.shape == (7, 3) and vertices.dtype == np.float32
    assert triangles.dtype == np.uint32
    np.testing.assert_array_equal(triangles, [[0, 1, 2], [3, 4, 5], [4, 5, 6]])


def test_panel_hides_options_that_do_not_apply():
    # The panel hides an option by the schema's rule (ui._applies = OptionSpec.applies_to);
    # its GL_METHODS (the methods marked with their device) are those the gl options apply to.
    import hyvox
    from hyvox_blender.core import panel_rules

    applies = lambda name, method: hyvox.option(name).applies_to(method)  # noqa: E731
    assert applies("tess_gamma", "tessellation")
    assert not applies("tess_gamma", "hybrid")
    assert applies("hybrid_cutoff", "hybrid") and not applies("hybrid_cutoff", "cpu")
    assert all(applies("gl_device", m) for m in panel_rules.GL_METHODS)
    assert not applies("gl_device", "cpu")
    assert applies("resolution", "cpu") and applies("threads", "reference")
    assert set(panel_rules.GL_METHODS) == {m for m in hyvox.METHODS if applies("gl_device", m)}
    software = panel_rules.gl_device_summary([{"index": 0, "name": "software", "software": True}])
    gpu = panel_rules.gl_device_summary(
        [{"index": 0, "name": "software", "software": True}, {"index": 1, "name": "H200", "software": False}]
    )
    assert software == {"name": "software", "software": True} and gpu == {"name": "H200", "software": False}
    assert panel_rules.gl_device_summary([]) is None
    assert "software" in panel_rules.method_note("hybrid", "hybrid", software)
    assert panel_rules.method_note("hybrid", "hybrid", gpu) == "GPU: H200"
    assert panel_rules.method_note("auto", "cpu", software) == "Auto: CPU here"
    assert panel_rules.method_note("cpu", "cpu", software) is None


def test_panel_summary_lines_are_short():
    from hyvox_blender.core import panel_rules

    record = {
        "volumes": [
            {
                "name": "Bunny",
                "voxel_counts": [13977],
                "dims": [64, 64, 50],
                "voxel_size": 0.0024328,
                "triangles": 69451,
                "method": "cpu",
                "frames": None,
            }
        ],
        "timings_ms": {"total": 67.0},
    }
    lines = panel_rules.summary_lines(record)
    assert lines[0] == "Bunny" and "  13,977 voxels" in lines and lines[-1] == "Took 0.07 s"
    assert max(len(line) for line in lines) <= 24
