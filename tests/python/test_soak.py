# SPDX-License-Identifier: GPL-3.0-or-later
# Soak: hundreds of calls in one process over every method (cpu, reference, triangle,
# fragment, hybrid, tessellation), surface and solid, attributes on cpu, and the errors a
# caller can run into (bad arrays, bad options, cancelled runs, unwritable outputs, damaged
# files). After a warm-up (the GL worker's context and program cache, allocator pools), the
# process's resident memory, its open file descriptors and the live GL objects must stay
# flat: a leak per call shows as growth over the measured rounds.
import ctypes
import os
import pathlib

import numpy as np
import pytest

import hyvox
from shapes import icosphere

GL_METHODS = ("triangle", "fragment", "hybrid")
WARM_UP_ROUNDS = 3
MEASURED_ROUNDS = 40
# Resident memory may move by allocator noise after malloc_trim; a leak of one 48³ grid's
# bits per call (14 KiB) would add ~14 MiB over the measured calls (~1000), one of its
# coords arrays far more.
RSS_SLACK_MIB = 4.0


def resident_mib():
    ctypes.CDLL("libc.so.6").malloc_trim(0)  # hand freed pages back so only live memory counts
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2**20


def open_fds():
    return sorted(os.listdir("/proc/self/fd"))


def one_round(vertices, triangles, tmp: pathlib.Path):
    """One of each: every method on surface and solid, attributes, and every kind of error."""
    counts = {}
    for method in ("cpu", "reference") + GL_METHODS:
        for mode in ("conservative", "solid"):
            grid = hyvox.voxelize(
                vertices, triangles, resolution=48 if method != "reference" else 24, method=method, mode=mode, threads=2
            )
            counts[method, mode] = grid.voxel_count
            assert grid.coords().shape == (grid.voxel_count, 3)
    counts["tessellation"] = hyvox.voxelize(vertices, triangles, resolution=48, method="tessellation").voxel_count
    colors = np.abs(vertices).astype(np.float32)
    grid = hyvox.voxelize(
        vertices, triangles, resolution=32, method="cpu", colors=colors, attributes=("color", "normal")
    )
    assert grid.attributes()["color"].shape == (grid.voxel_count, 3)
    out = tmp / "sphere.vdb"
    grid.write_vdb(str(out))
    assert out.stat().st_size > 0
    out.unlink()

    bad_vertices = vertices.copy()
    bad_vertices[3, 1] = np.nan
    with pytest.raises(ValueError, match="non-finite"):
        hyvox.voxelize(bad_vertices, triangles, resolution=16)
    with pytest.raises(ValueError):
        hyvox.voxelize(vertices, triangles + np.uint32(len(vertices)), resolution=16, method="triangle")
    with pytest.raises(ValueError):
        hyvox.voxelize(vertices[:, :2], triangles, resolution=16)
    with pytest.raises(ValueError):
        hyvox.voxelize(vertices, triangles, resolution=0)
    with pytest.raises(ValueError):
        hyvox.voxelize(vertices, triangles, method="no_such_method")
    with pytest.raises(TypeError):
        hyvox.voxelize(vertices, triangles, no_such_option=1)
    for method in ("cpu", "hybrid", "tessellation"):
        token = hyvox.CancelToken()
        token.cancel()
        with pytest.raises(hyvox.Cancelled):
            hyvox.voxelize(vertices, triangles, resolution=48, method=method, cancel=token)

    def stop(percent):
        raise KeyError("stopped by the progress callback")

    with pytest.raises(KeyError):
        hyvox.voxelize(vertices, triangles, resolution=48, method="fragment", progress=stop)
    with pytest.raises((OSError, RuntimeError, ValueError)):
        grid.write_vdb(str(tmp / "no_such_folder" / "x.vdb"))
    with pytest.raises((OSError, RuntimeError, ValueError)):
        grid.write_vdb(str(tmp))  # a folder, not a file
    damaged = tmp / "damaged.ply"
    damaged.write_bytes(
        b"ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\n"
        b"property float y\nproperty float z\nend_header\n" + bytes(100)
    )
    with pytest.raises(ValueError):
        hyvox.read_mesh(damaged)
    return counts


def test_soak_memory_descriptors_and_gl_objects_stay_flat(tmp_path):
    vertices, triangles = icosphere()
    first = None
    for _ in range(WARM_UP_ROUNDS):
        counts = one_round(vertices, triangles, tmp_path)
        first = first or counts
        assert counts == first  # every method is deterministic: the same voxels every time
    rss, fds, gl = resident_mib(), open_fds(), hyvox._core.gl_live_objects()
    assert gl["programs"] > 0 and gl["shaders"] == 0  # the cached programs; shaders freed once linked
    for _ in range(MEASURED_ROUNDS):
        assert one_round(vertices, triangles, tmp_path) == first
    assert open_fds() == fds
    assert hyvox._core.gl_live_objects() == gl
    grown = resident_mib() - rss
    print(
        f"soak: {MEASURED_ROUNDS} rounds, resident {rss:.1f} MiB -> {rss + grown:.1f} MiB, {len(fds)} fds, GL objects {gl}"
    )
    assert grown < RSS_SLACK_MIB, f"resident memory grew {grown:.1f} MiB over {MEASURED_ROUNDS} rounds"
    # The counts are real: the sphere covers voxels in every mode, solid more than surface.
    for method in ("cpu", "reference") + GL_METHODS:
        assert 0 < first[method, "conservative"] < first[method, "solid"]
