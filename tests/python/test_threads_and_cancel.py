# SPDX-License-Identifier: GPL-3.0-or-later
# The GIL is released while native code runs, and a CancelToken stops a run from another
# thread.
import threading
import time

import numpy as np
import pytest

import hyvox
import mesh_writers


class Counter(threading.Thread):
    """Counts in pure Python (needs the GIL) until stopped."""

    def __init__(self):
        super().__init__(daemon=True)
        self.count = 0
        self.stop = False

    def run(self):
        while not self.stop:
            self.count += 1


def counting_rate(seconds):
    counter = Counter()
    counter.start()
    time.sleep(seconds)
    counter.stop = True
    counter.join()
    return counter.count / seconds


def counted_share(run):
    """Share of the idle counting rate a Python thread keeps while run() executes."""
    rate = counting_rate(0.3)  # increments per second while this thread sleeps
    counter = Counter()
    counter.start()
    time.sleep(0.05)
    before = counter.count
    start = time.perf_counter()
    run()
    elapsed = time.perf_counter() - start
    during = counter.count - before
    counter.stop = True
    counter.join()
    return during / (rate * elapsed)


def test_gil_released_during_voxelization(dragon):
    vertices, triangles = dragon
    # With the GIL held the counter stalls for the whole native run (a share of about 0.02,
    # from the switch interval alone); released, it keeps a good part of a core (0.25-0.4
    # measured on a busy 2-core machine). Other tests may load the machine at the same
    # time, so a single attempt above 0.1 is enough.
    shares = []
    for _ in range(3):
        shares.append(counted_share(lambda: hyvox.voxelize(vertices, triangles, resolution=512)))
        if shares[-1] > 0.1:
            break
    assert max(shares) > 0.1, shares


def test_cancel_from_another_thread(dragon):
    vertices, triangles = dragon
    token = hyvox.CancelToken()
    assert token.progress == -1 and not token.cancelled and not token.running
    seen_running = threading.Event()

    def cancel_when_running():
        # This loop needs the GIL while the main thread is inside voxelize(): it runs only
        # because the GIL is released there.
        deadline = time.monotonic() + 60
        while not token.running and time.monotonic() < deadline:
            time.sleep(0.001)
        if token.running:
            seen_running.set()
        token.cancel()

    canceller = threading.Thread(target=cancel_when_running)
    canceller.start()
    start = time.perf_counter()
    with pytest.raises(hyvox.Cancelled):
        hyvox.voxelize(vertices, triangles, resolution=1024, method="reference", cancel=token)
    canceller.join()
    assert seen_running.is_set() and token.cancelled and not token.running
    assert time.perf_counter() - start < 30
    # The token can be reused once reset.
    token.reset()
    assert not token.cancelled and token.progress == -1


def test_cancelled_before_start(tetrahedron):
    vertices, triangles = tetrahedron
    token = hyvox.CancelToken()
    token.cancel()
    with pytest.raises(hyvox.Cancelled):
        hyvox.voxelize(vertices, triangles, resolution=8, cancel=token)


def test_progress_reaches_100(bunny):
    vertices, triangles = bunny
    token = hyvox.CancelToken()
    seen = []
    hyvox.voxelize(vertices, triangles, resolution=128, cancel=token, progress=seen.append)
    assert seen and seen == sorted(seen) and seen[-1] == 100
    assert all(isinstance(p, int) for p in seen)
    assert token.progress == 100 and not token.running


def test_progress_callback_exception_propagates(bunny):
    vertices, triangles = bunny

    def boom(percent):
        raise KeyError("stop here")

    with pytest.raises(KeyError, match="stop here"):
        hyvox.voxelize(vertices, triangles, resolution=64, progress=boom)
    with pytest.raises(TypeError):
        hyvox.voxelize(vertices, triangles, resolution=64, progress=42)


def test_concurrent_voxelizations_agree(bunny):
    vertices, triangles = bunny
    expected = hyvox.voxelize(vertices, triangles, resolution=96).coords()
    results = [None] * 4

    def work(n):
        results[n] = hyvox.voxelize(vertices, triangles, resolution=96).coords()

    threads = [threading.Thread(target=work, args=(n,)) for n in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r in results:
        assert np.array_equal(r, expected)


def test_read_mesh_stops_when_its_token_is_cancelled(mesh_dir, tmp_path):
    # Each reader asks the token at its milestones (tests/native/test_io_mesh_cancel.cpp has
    # the stops in the middle of a file); here the module's wiring: a cancelled token ends
    # read_mesh with hyvox.Cancelled for our readers and for assimp's formats, and a fresh
    # one reads the same arrays as no token.
    stl = tmp_path / "tri.stl"
    stl.write_text(
        "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
        "endloop\nendfacet\nendsolid t\n"
    )
    model = tmp_path / "tri.3mf"  # read by the assimp process
    model.write_bytes(mesh_writers.three_mf(np.eye(3, dtype=np.float32), np.array([[0, 1, 2]], np.uint32)))
    for path in (mesh_dir / "bunny_stanford_69k.ply", mesh_dir / "dragon_stanford_res2_203k.ply.gz", stl, model):
        token = hyvox.CancelToken()
        token.cancel()
        with pytest.raises(hyvox.Cancelled):
            hyvox.read_mesh(path, cancel=token)
        plain = hyvox.read_mesh(path)
        with_token = hyvox.read_mesh(path, cancel=hyvox.CancelToken())
        assert all(np.array_equal(a, b) for a, b in zip(plain, with_token))
    with pytest.raises(TypeError, match="CancelToken"):
        hyvox.read_mesh(stl, cancel=True)
