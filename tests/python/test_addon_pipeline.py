# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's run pipeline outside Blender: the real hyvox module when it is built
(PYTHONPATH=B/python), a stand-in for the cancel and failure paths."""

import os
import sys
import threading
import time

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "addon"))

from hyvox_blender.core import backend, summary  # noqa: E402
from hyvox_blender.core.errors import CancelledError, HyvoxError  # noqa: E402
from hyvox_blender.core.pipeline import Group, GroupMesh, Pipeline  # noqa: E402
from hyvox_blender.core.settings import VoxelizeSettings  # noqa: E402


def cube_mesh(size=2.0, shift=(0.0, 0.0, 0.0)):
    h = size / 2
    v = np.array(
        [(-h, -h, -h), (h, -h, -h), (h, h, -h), (-h, h, -h), (-h, -h, h), (h, -h, h), (h, h, h), (-h, h, h)], np.float32
    ) + np.float32(shift)
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    t = np.array([tri for a, b, c, d in quads for tri in ((a, b, c), (a, c, d))], np.uint32)
    return v, t


@pytest.fixture(scope="module")
def hyvox():
    # conftest.py imports hyvox already; a plain import fails loudly instead of skipping.
    import hyvox as module

    return module


def exporter(groups, shifts=None):
    def export(frame):
        out = []
        for g in groups:
            shift = (0.0, 0.0, 0.0) if frame is None or shifts is None else shifts[frame]
            v, t = cube_mesh(shift=shift)
            out.append(GroupMesh(g, v, t))
        return out

    return export


def test_single_volume(hyvox, tmp_path):
    settings = VoxelizeSettings(voxel_size=0.25, method="cpu")
    pipeline = Pipeline(settings, str(tmp_path), exporter([Group("Cube", ["Cube"])]), module=hyvox)
    results = pipeline.run()
    (result,) = results.values()
    assert result.files == [str(tmp_path / "Cube_voxels.vdb")]
    assert os.path.isfile(result.files[0])
    assert result.voxel_counts == [8**3 - 6**3]
    assert result.dims == (8, 8, 8) and result.voxel_size == 0.25
    assert sorted(os.listdir(tmp_path)) == ["Cube_voxels.vdb"]  # no staging files left
    assert "296 voxels" in summary.describe_result(result)
    assert summary.as_dict(results, pipeline.timings)["volumes"][0]["voxel_counts"] == [296]


def test_sequence_keeps_first_voxel_size(hyvox, tmp_path):
    shifts = {1: (0, 0, 0), 2: (1, 0, 0)}
    settings = VoxelizeSettings(resolution=8, method="cpu", frames=[1, 2])
    pipeline = Pipeline(settings, str(tmp_path), exporter([Group("C", ["C"])], shifts), module=hyvox)
    (result,) = pipeline.run().values()
    assert [os.path.basename(p) for p in result.files] == ["C_voxels_0001.vdb", "C_voxels_0002.vdb"]
    assert result.frames == [1, 2]
    assert result.voxel_size == pytest.approx(0.25)


def test_threaded_run_matches(hyvox, tmp_path):
    settings = VoxelizeSettings(resolution=16, method="cpu", frames=[1, 2, 3])
    pipeline = Pipeline(settings, str(tmp_path), exporter([Group("A", ["A"]), Group("B", ["B"])]), module=hyvox)
    while pipeline.start_next_frame():
        while pipeline.worker_busy():
            assert 0.0 <= pipeline.progress <= 1.0
            time.sleep(0.001)
        pipeline.finish_frame()
    pipeline.commit()
    assert not pipeline.worker_busy() and not pipeline.start_next_frame()
    assert len(os.listdir(tmp_path)) == 6


def test_auto_method_resolves(hyvox):
    # "auto" picks the hybrid only for a hardware EGL device (llvmpipe is slower than the
    # cpu method); the expected answer comes from the device list, not from the add-on.
    # (It used to accept either answer, so it could not fail.)
    hardware = any(not device["software"] for device in hyvox.gl_devices())
    method = backend.resolve_method(hyvox, "auto")
    assert method == ("hybrid" if hardware else "cpu")
    assert backend.resolve_method(hyvox, "fragment") == "fragment"


def test_native_errors_become_hyvox_errors(hyvox, tmp_path):
    def export(frame):
        v = np.array([[0, 0, 0], [np.nan, 0, 0], [0, 1, 0]], np.float32)
        return [GroupMesh(Group("Bad", ["Bad"]), v, np.array([[0, 1, 2]], np.uint32))]

    pipeline = Pipeline(VoxelizeSettings(method="cpu"), str(tmp_path), export, module=hyvox)
    with pytest.raises(HyvoxError):
        pipeline.run()
    assert os.listdir(tmp_path) == []


class SlowModule:
    """Stands in for hyvox: a voxelization that runs until cancelled."""

    class Cancelled(Exception):
        pass

    class CancelToken:
        def __init__(self):
            self.event = threading.Event()
            self.progress = -1

        def cancel(self):
            self.event.set()

    WRITE_OPTIONS = ()

    def ignored_options(self, method, names):
        return []

    def voxelize(self, vertices, triangles, cancel=None, **kw):
        cancel.progress = 50
        if cancel.event.wait(10):
            raise self.Cancelled()
        raise AssertionError("never cancelled")


def test_cancel_from_main_thread(tmp_path):
    module = SlowModule()
    pipeline = Pipeline(
        VoxelizeSettings(method="cpu"), str(tmp_path), exporter([Group("Cube", ["Cube"])]), module=module
    )
    assert pipeline.start_next_frame()
    while pipeline.progress == 0.0:
        time.sleep(0.001)
    assert pipeline.progress == pytest.approx(0.8 * 0.5)  # voxelizing is 80% of a group's share
    pipeline.cancel()
    pipeline.wait()
    with pytest.raises(CancelledError):
        pipeline.finish_frame()
    pipeline.discard()
    assert os.listdir(tmp_path) == []


class HeldWriteModule(SlowModule):
    """A voxelization that returns at once and a .vdb write that ignores the cancel token
    and waits until the test releases it."""

    def __init__(self):
        self.entered, self.release = threading.Event(), threading.Event()

    def voxelize(self, vertices, triangles, cancel=None, **kw):
        module = self

        class Grid:
            voxel_size, origin, dims, stats, voxel_count = 1.0, (0, 0, 0), (1, 1, 1), {}, 1

            def write_vdb(self, path, cancel=None, **options):
                with open(path, "w") as f:
                    f.write("staged")
                module.entered.set()
                assert module.release.wait(10)

        return Grid()


def test_abandon_does_not_wait_and_the_worker_deletes_what_it_staged(tmp_path):
    module = HeldWriteModule()
    pipeline = Pipeline(
        VoxelizeSettings(method="cpu"), str(tmp_path), exporter([Group("Cube", ["Cube"])]), module=module
    )
    assert pipeline.start_next_frame()
    assert module.entered.wait(10)
    assert len(os.listdir(tmp_path)) == 1  # the staged file, mid-write
    pipeline.abandon()  # returns although the write is still held
    assert not module.release.is_set() and pipeline.worker_busy()
    module.release.set()
    pipeline.wait()
    assert os.listdir(tmp_path) == []  # the worker deleted it on its way out


def test_failure_discards_earlier_frames(hyvox, tmp_path):
    calls = []

    def export(frame):
        calls.append(frame)
        if frame == 3:
            raise HyvoxError("object vanished")
        v, t = cube_mesh()
        return [GroupMesh(Group("C", ["C"]), v, t)]

    (tmp_path / "C_voxels_0001.vdb").write_bytes(b"previous")
    pipeline = Pipeline(
        VoxelizeSettings(resolution=8, method="cpu", frames=[1, 2, 3]), str(tmp_path), export, module=hyvox
    )
    with pytest.raises(HyvoxError):
        pipeline.run()
    assert calls == [1, 2, 3]
    # The previous file is untouched and no staging file lingers.
    assert sorted(os.listdir(tmp_path)) == ["C_voxels_0001.vdb"]
    assert (tmp_path / "C_voxels_0001.vdb").read_bytes() == b"previous"


def test_names_that_clean_alike_get_their_own_files(hyvox, tmp_path):
    groups = [Group("a/b", ["a/b"]), Group("a_b", ["a_b"])]
    pipeline = Pipeline(VoxelizeSettings(resolution=8, method="cpu"), str(tmp_path), exporter(groups), module=hyvox)
    results = pipeline.run()
    files = [r.files[0] for r in results.values()]
    assert len(set(files)) == 2
    assert len(os.listdir(tmp_path)) == 2


def test_groups_of_the_same_name_keep_their_own_files_across_runs(hyvox, tmp_path):
    # {A, B} then {A, C}: both volumes are called "A_and_1_more", and the second run must
    # not overwrite the file the first run's volume still reads.
    def run(sources, resolution):  # different resolutions: different file contents
        group = Group("A_and_1_more", sources)
        pipeline = Pipeline(
            VoxelizeSettings(resolution=resolution, method="cpu"), str(tmp_path), exporter([group]), module=hyvox
        )
        (result,) = pipeline.run().values()
        return result.files[0]

    first = run(["A", "B"], 8)
    before = open(first, "rb").read()
    second = run(["A", "C"], 6)
    assert first != second
    assert open(first, "rb").read() == before
    assert sorted(os.listdir(tmp_path)) == sorted(os.path.basename(p) for p in (first, second))


def test_an_output_folder_that_cannot_be_made_is_a_hyvox_error(hyvox, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_bytes(b"")
    pipeline = Pipeline(
        VoxelizeSettings(resolution=8, method="cpu"), str(blocker / "out"), exporter([Group("C", ["C"])]), module=hyvox
    )
    with pytest.raises(HyvoxError, match="cannot create the output folder"):
        pipeline.run()
    assert os.listdir(tmp_path) == ["file"]


def colour_exporter(group, colour):
    def export(frame):
        v, t = cube_mesh()
        return [GroupMesh(group, v, t, colour)]

    return export


def test_auto_keeps_hybrid_for_colour_now_that_it_makes_colour(hyvox, tmp_path, monkeypatch):
    monkeypatch.setattr(backend, "gl_available", lambda module, device="": True)
    colour = {"colors": np.tile(np.float32([0.25, 0.5, 0.75, 1.0]), (36, 1))}
    pipeline = Pipeline(
        VoxelizeSettings(voxel_size=0.25, color=True),
        str(tmp_path),
        colour_exporter(Group("C", ["C"]), colour),
        module=hyvox,
    )
    (result,) = pipeline.run().values()
    assert result.method == "hybrid" and result.has_color
    import pyopenvdb as vdb

    grid = vdb.read(result.files[0], "color")
    assert grid.activeVoxelCount() == result.voxel_counts[0]
    for item in grid.citerOnValues():
        np.testing.assert_allclose(item.value, (0.25, 0.5, 0.75), atol=1e-6)


def test_a_solid_run_stores_colour_on_every_voxel(hyvox, tmp_path):
    # Fill Interior with Colour: the inside takes the surface's colour (one colour here), and
    # the color grid has exactly the density's voxels, tiles included.
    colour = {"colors": np.tile(np.float32([0.25, 0.5, 0.75, 1.0]), (36, 1))}
    settings = VoxelizeSettings(voxel_size=0.05, color=True, method="cpu", mode="solid")
    pipeline = Pipeline(settings, str(tmp_path), colour_exporter(Group("C", ["C"]), colour), module=hyvox)
    (result,) = pipeline.run().values()
    assert result.has_color
    import pyopenvdb as vdb

    names = sorted(g.name for g in vdb.readAllGridMetadata(result.files[0]))
    assert names == ["alpha", "color", "density"]  # the colours are RGBA
    density, color = (vdb.read(result.files[0], name) for name in ("density", "color"))
    assert color.activeVoxelCount() == density.activeVoxelCount() == result.voxel_counts[0]
    tiles = [item for item in color.citerOnValues() if item.count > 1]
    assert tiles, "a 40-voxel solid cube has whole-brick tiles"
    for item in color.citerOnValues():
        np.testing.assert_allclose(item.value, (0.25, 0.5, 0.75), atol=1e-6)
    # Solid: more voxels than the cube's surface shell (the inside is filled).
    surface = Pipeline(
        VoxelizeSettings(voxel_size=0.05, method="cpu"),
        str(tmp_path / "s"),
        colour_exporter(Group("C", ["C"]), {}),
        module=hyvox,
    )
    (shell,) = surface.run().values()
    assert result.voxel_counts[0] > shell.voxel_counts[0]


def test_a_coloured_solid_vox_file_has_every_voxel_coloured(hyvox, tmp_path):
    # The .vox of Fill Interior + Colour: every solid voxel, inside ones included, in the cube's colour.
    from test_addon_blocks import parse_vox, voxels_of
    from hyvox_blender.core import vox

    colour = {"colors": np.tile(np.float32([0.25, 0.5, 0.75, 1.0]), (36, 1))}
    settings = VoxelizeSettings(voxel_size=0.1, color=True, method="cpu", mode="solid", export_vox=True)
    pipeline = Pipeline(settings, str(tmp_path), colour_exporter(Group("C", ["C"]), colour), module=hyvox)
    (result,) = pipeline.run().values()
    (path,) = result.vox_files
    got = voxels_of(parse_vox(open(path, "rb").read()))
    assert len(got) == result.voxel_counts[0] == 20**3  # a 2-unit cube at 0.1: 20³, all inside or surface
    assert set(got.values()) == {tuple(vox.linear_to_srgb8(np.array([[0.25, 0.5, 0.75]]))[0])}
