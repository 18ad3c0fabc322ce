# SPDX-License-Identifier: GPL-3.0-or-later
"""Live's bpy-free parts: the key of an input, the bounded cache, one run (voxels against
the module called directly), and the scheduler's state machine (one run per volume at most,
a burst of edits in at most two runs, newest wins, cancel drops)."""

import os
import sys
import threading

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "addon"))

from hyvox_blender.core import live_key  # noqa: E402
from hyvox_blender.core.live_cache import CacheEntry, LiveCache  # noqa: E402
from hyvox_blender.core.live_run import LiveInput, LiveRun  # noqa: E402
from hyvox_blender.core.live_scheduler import DROPPED, FAILED, SHOWN, LiveScheduler  # noqa: E402
from hyvox_blender.core.pipeline import Group, GroupMesh, GroupResult  # noqa: E402
from hyvox_blender.core.settings import VoxelizeSettings  # noqa: E402
from lattice_oracle import snapped_origin  # noqa: E402
from shapes import icosphere  # noqa: E402

GROUP = Group("Ball", ["Ball"])


@pytest.fixture(scope="module")
def hyvox():
    import hyvox as module

    return module


def ball(shift=0.0, scale=1.0):
    v, t = icosphere(2)
    return GroupMesh(GROUP, (v * np.float32(scale) + np.float32([shift, 0, 0])).astype(np.float32), t)


def live_input(tmp_path, mesh, voxel_size=0.1, mode="conservative", **kw):
    settings = VoxelizeSettings(method="cpu", voxel_size=voxel_size, mode=mode, fixed_lattice=True)
    fingerprint = live_key.options_fingerprint(dict(settings.options, method="cpu"))
    return LiveInput([mesh], settings, str(tmp_path), fingerprint, owner="Ball_voxels", **kw)


# -- the key ------------------------------------------------------------------------------
def test_the_key_follows_geometry_colour_and_options():
    a, b = ball(), ball(shift=1e-3)
    fingerprint = live_key.options_fingerprint({"voxel_size": 0.1, "mode": "solid"})
    key = live_key.run_key(live_key.geometry_digest([a]), fingerprint)
    assert key == live_key.run_key(live_key.geometry_digest([ball()]), fingerprint)  # equal input
    assert key != live_key.run_key(live_key.geometry_digest([b]), fingerprint)
    assert key != live_key.run_key(
        live_key.geometry_digest([a]), live_key.options_fingerprint({"voxel_size": 0.1, "mode": "thin"})
    )
    coloured = GroupMesh(GROUP, a.vertices, a.triangles, {"colors": np.ones((len(a.triangles) * 3, 3), np.float32)})
    recoloured = GroupMesh(GROUP, a.vertices, a.triangles, {"colors": np.zeros((len(a.triangles) * 3, 3), np.float32)})
    assert len({live_key.geometry_digest([m]) for m in (a, coloured, recoloured)}) == 3
    # Option order does not matter.
    assert live_key.options_fingerprint({"a": 1, "b": 2}) == live_key.options_fingerprint({"b": 2, "a": 1})


# -- the cache ----------------------------------------------------------------------------
def _entry(tmp_path, key, size, owner="V"):
    path = tmp_path / f"{key}_voxels_r000000x.vdb"
    path.write_bytes(b"x" * size)
    return CacheEntry(key, GroupResult(GROUP, files=[str(path)]), owner=owner)


def test_the_cache_evicts_the_least_recently_used_past_its_disk_bound(tmp_path):
    cache = LiveCache(max_disk_bytes=250)
    for key in "abc":
        cache.put(_entry(tmp_path, key, 100))
    # c pushed the cache to 300 bytes: a, the oldest, went, with its file.
    assert "a" not in cache and "b" in cache and "c" in cache
    assert sorted(os.listdir(tmp_path)) == ["b_voxels_r000000x.vdb", "c_voxels_r000000x.vdb"]
    assert cache.get("b") is not None  # b is now the most recently used...
    cache.put(_entry(tmp_path, "d", 100))
    assert "c" not in cache and "b" in cache  # ...so c goes next
    assert cache.disk_bytes == 200


def test_files_in_use_are_never_deleted(tmp_path):
    shown = []
    cache = LiveCache(max_disk_bytes=150, in_use=lambda: shown)
    first = _entry(tmp_path, "a", 100)
    cache.put(first)
    shown.append(first.files[0])  # a volume shows a
    cache.put(_entry(tmp_path, "b", 100))  # b is about to be shown: over the bound, both stay
    assert "a" in cache and "b" in cache
    cache.put(_entry(tmp_path, "c", 100))
    assert os.path.exists(first.files[0]) and "a" in cache and "c" in cache
    assert "b" not in cache and not os.path.exists(str(tmp_path / "b_voxels_r000000x.vdb"))


def test_the_memory_bound_counts_blocks(tmp_path):
    from hyvox_blender.core.blocks import blocks_mesh

    def with_blocks(key, voxels):
        entry = _entry(tmp_path, key, 10)
        entry.result.blocks = blocks_mesh(np.array([[x, 0, 0] for x in range(0, 2 * voxels, 2)]), 1.0, (0, 0, 0), None)
        return CacheEntry(key, entry.result)

    small, big = with_blocks("a", 1), with_blocks("b", 10)
    assert 0 < small.memory_bytes < big.memory_bytes  # the Blocks mesh's arrays
    cache = LiveCache(max_memory_bytes=small.memory_bytes + big.memory_bytes - 1)
    cache.put(small)
    cache.put(big)
    assert "a" not in cache and "b" in cache and cache.memory_bytes == big.memory_bytes


def test_a_missing_file_is_a_miss_and_owners_drop_their_entries(tmp_path):
    cache = LiveCache()
    a, b, c = _entry(tmp_path, "a", 1), _entry(tmp_path, "b", 1, owner="W"), _entry(tmp_path, "c", 1)
    for entry in (a, b, c):
        cache.put(entry)
    os.remove(a.files[0])
    assert cache.get("a") is None and "a" not in cache
    assert cache.drop_owner("V", protected=c.files) == []  # c is shown: kept on disk
    assert "c" not in cache and os.path.exists(c.files[0]) and "b" in cache


def test_clear_deletes_what_the_cache_wrote_except_the_protected(tmp_path):
    cache = LiveCache()
    a, b = _entry(tmp_path, "a", 1), _entry(tmp_path, "b", 1)
    cache.put(a)
    cache.put(b)
    other = tmp_path / "Other_voxels.vdb"
    other.write_bytes(b"not the cache's")
    cache.clear(protected=b.files)
    assert sorted(os.listdir(tmp_path)) == ["Other_voxels.vdb", "b_voxels_r000000x.vdb"]
    assert len(cache) == 0


# -- one run ------------------------------------------------------------------------------
def _file_world_voxels(path):
    import pyopenvdb as vdb

    grid = vdb.read(path, "density")
    size = grid.transform.voxelSize()[0]
    return {
        tuple(int(round(c / size - 0.5)) for c in grid.transform.indexToWorld(item.min))
        for item in grid.citerOnValues()
    }


@pytest.mark.parametrize("mode", ["conservative", "solid"])
def test_a_run_writes_the_modules_voxels_on_the_fixed_lattice(hyvox, tmp_path, mode):
    mesh = ball(shift=0.3137, scale=0.9)
    cache = LiveCache()
    output = LiveRun(live_input(tmp_path, mesh, mode=mode), cache)()
    assert not output.cached and len(output.result.files) == 1
    origin = snapped_origin(mesh.vertices, mesh.triangles, 0.1)
    oracle = hyvox.voxelize(mesh.vertices, mesh.triangles, voxel_size=0.1, origin=origin, method="reference", mode=mode)
    offset = np.array([round(o / 0.1) for o in oracle.origin])
    assert _file_world_voxels(output.result.files[0]) == {tuple(p) for p in oracle.coords().astype(np.int64) + offset}
    assert os.listdir(tmp_path) == [os.path.basename(output.result.files[0])]  # nothing staged is left


def test_the_same_input_again_comes_from_the_cache(hyvox, tmp_path, monkeypatch):
    from hyvox_blender.core import backend

    calls = []
    real = backend.voxelize
    monkeypatch.setattr(backend, "voxelize", lambda *a, **kw: calls.append(1) or real(*a, **kw))
    cache = LiveCache()
    first = LiveRun(live_input(tmp_path, ball()), cache)()
    again = LiveRun(live_input(tmp_path, ball()), cache)()
    moved = LiveRun(live_input(tmp_path, ball(shift=0.05)), cache)()
    assert len(calls) == 2 and again.cached and again.key == first.key
    assert again.result.files == first.result.files and moved.key != first.key
    assert len(os.listdir(tmp_path)) == 2


def test_a_failed_run_leaves_no_file(hyvox, tmp_path):
    bad = ball()
    bad.vertices[3] = np.nan
    run = LiveRun(live_input(tmp_path, bad), LiveCache())
    from hyvox_blender.core.errors import HyvoxError

    with pytest.raises(HyvoxError):
        run()
    assert os.listdir(tmp_path) == []


# -- the scheduler ------------------------------------------------------------------------
class FakeRun:
    """A run that holds until released (or cancelled), recording how many run at once."""

    running = 0
    most_at_once = 0
    lock = threading.Lock()

    def __init__(self, state, fail=""):
        self.state, self.fail = state, fail
        self.release = threading.Event()
        self.entered = threading.Event()
        self.cancelled = False

    def cancel(self):
        self.cancelled = True
        self.release.set()

    def __call__(self):
        with FakeRun.lock:
            FakeRun.running += 1
            FakeRun.most_at_once = max(FakeRun.most_at_once, FakeRun.running)
        try:
            self.entered.set()
            assert self.release.wait(10)
            from hyvox_blender.core.errors import CancelledError, HyvoxError

            if self.cancelled:
                raise CancelledError("cancelled")
            if self.fail:
                raise HyvoxError(self.fail)
            return self.state
        finally:
            with FakeRun.lock:
                FakeRun.running -= 1


def drive(scheduler, ident, state, runs):
    """What the Blender side's timer does on each tick: collect, then start if dirty."""
    outcome = scheduler.collect(ident)
    if scheduler.needs_run(ident):
        run = FakeRun(state["now"])
        runs.append(run)
        scheduler.start(ident, run)
    return outcome


def test_a_burst_of_edits_during_a_run_gives_one_more_run_with_the_last_state():
    scheduler = LiveScheduler(threaded=True)
    state, runs, shown = {"now": 0}, [], []
    scheduler.mark_dirty("V")
    drive(scheduler, "V", state, runs)
    assert runs[0].entered.wait(5)
    for edit in range(1, 11):  # ten edits while the first run is held
        state["now"] = edit
        scheduler.mark_dirty("V")
        assert drive(scheduler, "V", state, runs) is None
    assert len(runs) == 1 and scheduler.busy("V")
    runs[0].release.set()
    while len(runs) < 2:
        outcome = drive(scheduler, "V", state, runs)
        if outcome is not None:
            shown.append((outcome.kind, outcome.output))
    runs[1].release.set()
    scheduler.wait("V")
    outcome = drive(scheduler, "V", state, runs)
    shown.append((outcome.kind, outcome.output))
    assert len(runs) == 2 and FakeRun.most_at_once == 1
    # The first run's result was shown (nothing newer was), then the last edit's state.
    assert shown == [(SHOWN, 0), (SHOWN, 10)] and scheduler.get("V").last_output == 10
    assert not scheduler.active()


def test_cancel_drops_the_result_and_the_volume_stays_busy_until_the_run_ends():
    scheduler = LiveScheduler(threaded=True)
    run = FakeRun("never shown")
    scheduler.mark_dirty("V")
    scheduler.start("V", run)
    assert run.entered.wait(5)
    scheduler.cancel("V")
    assert run.cancelled
    scheduler.wait("V")
    outcome = scheduler.collect("V")
    assert outcome.kind == DROPPED and scheduler.get("V").last_output is None
    assert scheduler.get("V").state == "idle"


def test_forgetting_a_volume_leaves_its_run_to_collect_as_an_orphan():
    scheduler = LiveScheduler(threaded=True)
    run = FakeRun("late")
    scheduler.start("V", run)
    assert run.entered.wait(5)
    scheduler.cancel("V", forget=True)
    assert scheduler.get("V") is None and scheduler.active()
    outcomes = scheduler.shutdown()
    assert [o.kind for o in outcomes] == [DROPPED] and not scheduler.active()


def test_an_error_is_kept_with_the_last_good_result():
    scheduler = LiveScheduler(threaded=False)
    good = FakeRun("good")
    good.release.set()
    scheduler.start("V", good)
    assert scheduler.collect("V").kind == SHOWN
    bad = FakeRun("bad", fail="the mesh has no faces")
    bad.release.set()
    scheduler.start("V", bad)
    outcome = scheduler.collect("V")
    assert outcome.kind == FAILED and outcome.error == "the mesh has no faces"
    volume = scheduler.get("V")
    assert volume.error == "the mesh has no faces" and volume.last_output == "good"
    again = FakeRun("fixed")
    again.release.set()
    scheduler.start("V", again)
    assert scheduler.collect("V").kind == SHOWN and volume.error == ""


def test_a_synchronous_start_cancels_and_waits_for_a_threaded_run():
    """A render (synchronous) while the viewport's run of the same volume is still going:
    that run is cancelled and has ended before the render's starts."""
    scheduler = LiveScheduler(threaded=True)
    viewport = FakeRun("viewport")
    scheduler.start("V", viewport)
    assert viewport.entered.wait(5)
    render = FakeRun("render")
    render.release.set()
    scheduler.start("V", render, synchronous=True)
    assert viewport.cancelled and FakeRun.most_at_once == 1
    assert scheduler.collect("V").output == "render"
