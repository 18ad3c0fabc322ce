# SPDX-License-Identifier: GPL-3.0-or-later
# A process forked after a GL voxelization (multiprocessing's default "fork" start method on
# Linux) used to hang forever on any GL method: the worker thread owning the context stays
# in the parent. The child now gets a clear hyvox.BackendError for GL methods, and the CPU
# methods and the device list keep working there. The join timeout is only a safety net
# against a hang; what is asserted is the child's outcome.
import multiprocessing

import numpy as np
import pytest

import hyvox

TETRA = (
    np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32),
    np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], np.uint32),
)


def child_outcome(queue, method):
    try:
        queue.put(("ok", hyvox.voxelize(*TETRA, resolution=16, method=method).coords().tolist()))
    except Exception as e:  # the outcome is the assertion, whatever it is
        queue.put((type(e).__name__, str(e)))


def run_in_forked_child(method):
    context = multiprocessing.get_context("fork")
    queue = context.Queue()
    child = context.Process(target=child_outcome, args=(queue, method))
    child.start()
    child.join(120)
    if child.is_alive():
        child.kill()
        child.join()
        pytest.fail(f"the forked child hung on the {method} method")
    assert child.exitcode == 0
    return queue.get(timeout=10)


def test_a_child_forked_after_gl_gets_a_clear_error_for_gl_and_runs_cpu():
    parent = hyvox.voxelize(*TETRA, resolution=16, method="hybrid").coords().tolist()  # GL is in use now
    for method in ("hybrid", "tessellation"):
        kind, message = run_in_forked_child(method)
        assert kind == "BackendError", message
        assert "forked from one that had already used GL" in message and "'spawn'" in message
    # The exact CPU method gives the parent's voxels (all exact methods agree on a mesh).
    assert run_in_forked_child("cpu") == ("ok", parent)
    # And the parent's own GL keeps working after the fork.
    assert hyvox.voxelize(*TETRA, resolution=16, method="hybrid").coords().tolist() == parent


def test_a_spawned_process_runs_gl():
    hyvox.voxelize(*TETRA, resolution=16, method="hybrid")
    context = multiprocessing.get_context("spawn")
    queue = context.Queue()
    child = context.Process(target=child_outcome, args=(queue, "hybrid"))
    child.start()
    child.join(300)
    if child.is_alive():
        child.kill()
        pytest.fail("the spawned child hung")
    kind, coords = queue.get(timeout=10)
    assert kind == "ok" and coords == hyvox.voxelize(*TETRA, resolution=16, method="cpu").coords().tolist()
