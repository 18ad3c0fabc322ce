# SPDX-License-Identifier: GPL-3.0-or-later
# Fault injection at every front door (issue 16): a full disk (a file-size limit, set in the
# child process only, with SIGXFSZ ignored so the write gets EFBIG as it would ENOSPC), an
# unwritable destination, and a grid far larger than the machine's memory. Each ends in a
# clear error or a right result; never a half-written file or a replaced old one.
import os
import pathlib
import resource
import signal
import stat
import subprocess
import sys
import textwrap


import hyvox

REPO = pathlib.Path(__file__).resolve().parents[2]
FILE_LIMIT = 4096  # bytes: below any .vdb of the bunny, above the small files of the setup


def with_file_limit():
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # ignored dispositions survive exec
    resource.setrlimit(resource.RLIMIT_FSIZE, (FILE_LIMIT, FILE_LIMIT))


def previous_file(folder: pathlib.Path) -> pathlib.Path:
    old = folder / "out.vdb"
    old.write_text("previous contents")
    old.chmod(0o640)
    return old


def assert_untouched(old: pathlib.Path, *others: str):
    assert old.read_text() == "previous contents"
    assert stat.S_IMODE(old.stat().st_mode) == 0o640
    assert sorted(os.listdir(old.parent)) == sorted([old.name, *others])  # no temporary left


def run_child(script: str, **kw):
    env = dict(
        os.environ, PYTHONPATH=os.pathsep.join([os.path.dirname(os.path.dirname(hyvox.__file__)), str(REPO / "addon")])
    )
    return subprocess.run(
        [sys.executable, "-c", textwrap.dedent(script)], capture_output=True, text=True, timeout=300, env=env, **kw
    )


def test_cli_with_a_full_disk_keeps_the_old_file(cli_voxelize, mesh_dir, tmp_path):
    old = previous_file(tmp_path)
    bunny = mesh_dir / "bunny_stanford_69k.ply"
    # out.vdb in the folder the CLI runs in: the error names the path as it was given.
    done = cli_voxelize(bunny, "out.vdb", "--resolution", "64", timeout=300, cwd=tmp_path, preexec_fn=with_file_limit)
    assert done.returncode == 1
    assert done.stderr == "hyvox: error: writing 'out.vdb' failed: File too large\n"
    assert_untouched(old)
    # Without the limit the same command writes the file (the limit was the only cause).
    done = cli_voxelize(bunny, "out.vdb", "--resolution", "64", "-q", timeout=300, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert old.stat().st_size > FILE_LIMIT and stat.S_IMODE(old.stat().st_mode) == 0o640


def test_cli_into_an_unwritable_folder_is_a_clear_error(cli_voxelize, mesh_dir):
    # /proc refuses new files even to root (who ignores a folder's mode bits).
    done = cli_voxelize(mesh_dir / "bunny_stanford_69k.ply", "/proc/out.vdb", "--resolution", "16", timeout=300)
    assert done.returncode == 1
    assert done.stderr.startswith("hyvox: error: cannot write '/proc/out.vdb': cannot create a file in folder '/proc'")
    assert not os.path.exists("/proc/out.vdb")


def test_module_write_vdb_with_a_full_disk_raises_resource_error(tmp_path):
    old = previous_file(tmp_path)
    done = run_child(
        f"""
        import hyvox, numpy as np
        grid = hyvox.voxelize(np.random.default_rng(1).random((300, 3), np.float32),
                              np.arange(300, dtype=np.uint32).reshape(100, 3), resolution=64)
        try:
            grid.write_vdb({str(old)!r})
        except hyvox.ResourceError as e:
            print("ResourceError:", e)
    """,
        preexec_fn=with_file_limit,
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("ResourceError: writing ") and "File too large" in done.stdout, done.stdout
    assert_untouched(old)


def test_addon_pipeline_with_a_full_disk_reports_and_leaves_no_file(tmp_path):
    old = previous_file(tmp_path)
    done = run_child(
        f"""
        import numpy as np, hyvox
        from hyvox_blender.core.errors import HyvoxError
        from hyvox_blender.core.pipeline import Group, GroupMesh, Pipeline
        from hyvox_blender.core.settings import VoxelizeSettings
        rng = np.random.default_rng(2)
        mesh = (rng.random((300, 3), np.float32), np.arange(300, dtype=np.uint32).reshape(100, 3))
        pipeline = Pipeline(VoxelizeSettings(method="cpu", resolution=64), {str(tmp_path)!r},
                            lambda frame: [GroupMesh(Group("Noise", ["Noise"]), *mesh)], module=hyvox)
        try:
            pipeline.run()
        except HyvoxError as e:
            print("HyvoxError:", e)
    """,
        preexec_fn=with_file_limit,
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("HyvoxError:") and "File too large" in done.stdout, done.stdout
    assert_untouched(old)


def test_a_grid_far_larger_than_memory_over_a_small_surface_runs_in_little_memory():
    # 16384³ voxels (512 GiB as bits) under a budget that allows it, in a child limited to
    # 16 GiB of address space: the tile's bits are taken where the surface is, so the run
    # neither fails to allocate nor is killed, and its voxels are those of a small grid at
    # the same voxel size and origin (the oracle: the same voxels, found without the big grid).
    done = run_child("""
        import resource, hyvox, numpy as np
        resource.setrlimit(resource.RLIMIT_AS, (16 << 30, 16 << 30))
        v = np.array([[0, 0, 0], [1e-3, 0, 0], [0, 1e-3, 0]], np.float32)
        t = np.array([[0, 1, 2]], np.uint32)
        big = hyvox.voxelize(v, t, bounds=((0, 0, 0), (1, 1, 1)), resolution=16384, memory_budget_mib=2**30)
        small = hyvox.voxelize(v, t, origin=(0, 0, 0), voxel_size=1 / 16384)
        assert big.dims == (16384, 16384, 16384) and big.voxel_size == small.voxel_size
        assert big.voxel_count > 0 and np.array_equal(big.coords(), small.coords())
        print("same", big.voxel_count)
    """)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("same ")
