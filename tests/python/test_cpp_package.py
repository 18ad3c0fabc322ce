# SPDX-License-Identifier: GPL-3.0-or-later
# The C++ package as a user gets it: `cmake --install` of this build into a fresh prefix, the
# example program (examples/cpp/) configured with find_package(hyvox) against that prefix
# alone, built and run. Its voxel counts are the Python module's for the same mesh and
# options, and a GL method runs through the plugin installed beside libhyvox.so.
import os
import pathlib
import re
import shutil
import subprocess

import hyvox

BUILD = pathlib.Path(hyvox.__file__).resolve().parents[2]
EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "cpp"


def run(command, **kw):
    done = subprocess.run([str(c) for c in command], capture_output=True, text=True, timeout=600, **kw)
    assert done.returncode == 0, f"{command}\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}"
    return done


def test_installed_package_builds_the_example_and_gives_the_modules_voxels(mesh_dir, bunny, tmp_path):
    cmake = shutil.which("cmake", path="/usr/bin:/bin") or "cmake"
    prefix = tmp_path / "prefix"
    run([cmake, "--install", BUILD, "--prefix", prefix])
    assert (prefix / "include" / "hyvox" / "voxelize.h").exists()
    assert not (prefix / "hyvox").exists()  # the wheel's component is not installed with it
    installed = sorted(p.name for p in (prefix / "lib").iterdir())
    assert {"libhyvox_gl_methods.so", "hyvox_assimp_reader"} <= set(installed), installed

    example = tmp_path / "example"
    run(
        [
            cmake,
            "-S",
            EXAMPLE,
            "-B",
            example,
            "-G",
            "Ninja",
            f"-DCMAKE_PREFIX_PATH={prefix}",
            "-DCMAKE_BUILD_TYPE=Release",
        ]
    )
    run([cmake, "--build", example])
    program = example / "voxel_count"
    mesh = mesh_dir / "bunny_stanford_69k.ply"
    expected = hyvox.voxelize(*bunny, resolution=64, method="cpu").voxel_count
    env = {k: v for k, v in os.environ.items() if k != "HYVOX_PLUGIN_DIR"}
    out = run([program, mesh, "64", "cpu", tmp_path / "b.vdb"], env=env).stdout
    count = int(re.match(r"(\d+) voxels in a (\d+x\d+x\d+) grid", out).group(1))
    assert count == expected > 0, out
    assert (tmp_path / "b.vdb").stat().st_size > 0

    # The hybrid method (exact: the cpu method's voxels) through the installed plugin: the
    # dynamic linker's own record says which file it loaded.
    traced = run([program, mesh, "64", "hybrid"], env={**env, "LD_DEBUG": "files"})
    assert int(traced.stdout.split()[0]) == count, traced.stdout
    opened = [line.split("file=")[1].split()[0] for line in traced.stderr.splitlines() if "file=" in line]
    plugins = {os.path.realpath(p) for p in opened if p.endswith("libhyvox_gl_methods.so")}
    assert plugins == {os.path.realpath(prefix / "lib" / "libhyvox_gl_methods.so")}, plugins
