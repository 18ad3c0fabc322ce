# SPDX-License-Identifier: GPL-3.0-or-later
# The plugins (native/src/core/plugin_library.h): the GL stack is loaded only when a method
# needs it, and libassimp never (the formats read through assimp are read by the helper
# program hyvox_assimp_reader, in a process of its own), and what needs them still works,
# from the CLI and the module. Which libraries a process loaded is asked of the dynamic linker (LD_DEBUG=files)
# or the kernel (/proc/self/maps), not of hyvox; the voxels of a run through a plugin are
# compared with the same mesh through hyvox's own readers and the cpu method.
import json
import os
import pathlib
import subprocess
import sys

import numpy as np

import hyvox
import mesh_writers

# What assimp brings: it belongs in no hyvox process but the assimp reader's.
ASSIMP = ("libassimp.so", "libdraco.so")
GL = ("libhyvox_gl_methods.so", "libepoxy.so", "libEGL.so")
PYTHONPATH = str(pathlib.Path(hyvox.__file__).resolve().parents[1])


def tetra_3mf(path, vertices, triangles):
    """The mesh as 3MF (a format only assimp reads here)."""
    path.write_bytes(mesh_writers.three_mf(np.asarray(vertices, np.float32), np.asarray(triangles, np.uint32)))
    return path


def loaded_by(command, env=None):
    """The shared objects the dynamic linker opened for `command` (LD_DEBUG=files), and its result."""
    done = subprocess.run(
        command, capture_output=True, text=True, timeout=300, env={**(env or os.environ), "LD_DEBUG": "files"}
    )
    opened = {line.split("file=")[1].split()[0] for line in done.stderr.splitlines() if "file=" in line}
    return {os.path.basename(name) for name in opened}, done


def has_any(names, libraries):
    return [n for n in names if any(n.startswith(lib) for lib in libraries)]


def voxels_of(path):
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "blender"))
    import vdb_dump  # pyopenvdb: an independent reader

    coords, _, _, _ = vdb_dump.read(str(path))
    return set(map(tuple, np.asarray(coords).reshape(-1, 3).tolist()))


def test_cli_cpu_run_of_ply_and_obj_loads_no_plugin(cli, mesh_dir, tetra_obj, tmp_path):
    for mesh in (mesh_dir / "bunny_stanford_69k.ply", tetra_obj):
        names, done = loaded_by(
            [str(cli), "voxelize", str(mesh), "-o", str(tmp_path / "o.vdb"), "-q", "--resolution=32", "--method=cpu"]
        )
        assert done.returncode == 0, done.stderr[-2000:]
        assert "libtbb.so.12" in names  # the witness sees what the CLI loads
        assert not has_any(names, ASSIMP + GL + ("libopenvdb.so",)), names


def test_cli_reads_3mf_through_the_assimp_reader(cli, tetrahedron, tetra_obj, tmp_path):
    model = tetra_3mf(tmp_path / "tetra.3mf", *tetrahedron)
    names, done = loaded_by(
        [str(cli), "voxelize", str(model), "-o", str(tmp_path / "3mf.vdb"), "-q", "--resolution=16"]
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert "libtbb.so.12" in names  # the witness sees what the CLI loads
    assert not has_any(names, ASSIMP + GL), names
    subprocess.run(
        [str(cli), "voxelize", str(tetra_obj), "-o", str(tmp_path / "obj.vdb"), "-q", "--resolution=16"],
        check=True,
        timeout=120,
    )
    model_voxels = voxels_of(tmp_path / "3mf.vdb")
    assert model_voxels and model_voxels == voxels_of(tmp_path / "obj.vdb")


def test_cli_gl_method_through_the_gl_plugin(cli, tetra_obj, tmp_path):
    names, done = loaded_by(
        [
            str(cli),
            "voxelize",
            str(tetra_obj),
            "-o",
            str(tmp_path / "gl.vdb"),
            "-q",
            "--resolution=16",
            "--method=hybrid",
        ]
    )
    assert done.returncode == 0, done.stderr[-2000:]
    assert has_any(names, ("libhyvox_gl_methods.so",)) and has_any(names, ("libepoxy.so",)), names
    assert not has_any(names, ASSIMP), names
    subprocess.run(
        [
            str(cli),
            "voxelize",
            str(tetra_obj),
            "-o",
            str(tmp_path / "cpu.vdb"),
            "-q",
            "--resolution=16",
            "--method=cpu",
        ],
        check=True,
        timeout=120,
    )
    gl_voxels = voxels_of(tmp_path / "gl.vdb")
    assert gl_voxels and gl_voxels == voxels_of(tmp_path / "cpu.vdb")  # the exact methods agree


MODULE_CHILD = r"""
import json, sys
import numpy as np
import hyvox

def mapped():
    with open("/proc/self/maps") as maps:
        return sorted({l.split()[5].rsplit("/", 1)[-1] for l in maps if len(l.split()) >= 6 and ".so" in l.split()[5]})

out = {"import": mapped()}
v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32)
t = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], np.uint32)
cpu = hyvox.voxelize(v, t, resolution=16, method="cpu")
out["live_before_gl"] = hyvox._core.gl_live_objects()
out["cpu"] = mapped()
gl = hyvox.voxelize(v, t, resolution=16, method="hybrid")
out["gl"] = mapped()
out["gl_equals_cpu"] = bool(np.array_equal(gl.coords(), cpu.coords())) and len(cpu.coords()) > 0
out["devices"] = hyvox._core.gl_devices()
model = hyvox.read_mesh(sys.argv[1])
out["model"] = mapped()
out["model_equals"] = bool(np.array_equal(np.asarray(model[0])[np.asarray(model[1])], v[t]))  # the same triangles
print(json.dumps(out))
"""


def test_module_loads_each_plugin_when_first_needed(tetrahedron, tmp_path):
    model = tetra_3mf(tmp_path / "tetra.3mf", *tetrahedron)
    done = subprocess.run(
        [sys.executable, "-c", MODULE_CHILD, str(model)],
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, "PYTHONPATH": PYTHONPATH},
    )
    assert done.returncode == 0, done.stderr[-3000:]
    out = json.loads(done.stdout)
    assert any(n.startswith("_core") for n in out["cpu"])
    assert not has_any(out["cpu"], ASSIMP + GL), out["cpu"]
    assert out["live_before_gl"] == dict.fromkeys(out["live_before_gl"], 0)  # asked without loading GL
    assert has_any(out["gl"], GL[:2]) and not has_any(out["gl"], ASSIMP), out["gl"]
    assert out["gl_equals_cpu"]
    assert out["devices"] and all({"index", "name", "software"} <= set(d) for d in out["devices"])
    assert not has_any(out["model"], ASSIMP), out["model"]
    assert out["model_equals"]


def test_a_missing_plugin_is_a_clear_error_and_nothing_else_needs_it(cli, tetrahedron, tetra_obj, tmp_path):
    empty = tmp_path / "no_plugins"
    empty.mkdir()
    env = {**os.environ, "HYVOX_PLUGIN_DIR": str(empty)}
    model = tetra_3mf(tmp_path / "tetra.3mf", *tetrahedron)
    run = lambda *args: subprocess.run(
        [str(cli), "voxelize", *map(str, args), "-o", str(tmp_path / "o.vdb"), "-q", "--resolution=8"],
        capture_output=True,
        text=True,
        timeout=120,
        env=env,
    )
    done = run(model)
    assert done.returncode != 0 and not (tmp_path / "o.vdb").exists()
    assert (
        f"reading '{model}' needs hyvox_assimp_reader, which is not installed with hyvox (looked in {empty})"
        in done.stderr
    ), done.stderr
    done = run(tetra_obj, "--method=hybrid")
    assert done.returncode != 0 and not (tmp_path / "o.vdb").exists()
    assert "the hybrid method needs libhyvox_gl_methods.so, which is not installed with hyvox" in done.stderr, (
        done.stderr
    )
    done = run(tetra_obj, "--method=cpu")  # a cpu run of an OBJ needs neither
    assert done.returncode == 0, done.stderr
    # The module: a RuntimeError with the same message.
    child = (
        "import hyvox\n"
        "try:\n    hyvox.voxelize([[0.,0,0],[1.,0,0],[0.,1,0]], [[0,1,2]], method='tessellation')\n"
        "except RuntimeError as e:\n    print(e)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", child],
        capture_output=True,
        text=True,
        timeout=120,
        env={**env, "PYTHONPATH": PYTHONPATH},
    )
    assert "the tessellation method needs libhyvox_gl_methods.so, which is not installed" in done.stdout, (
        done.stdout + done.stderr
    )


def hybrid_run_with_plugins_in(cli_voxelize, tetra_obj, out, folder):
    """The CLI's hybrid method (it needs the GL plugin) on the tetrahedron, with plugins looked
    for in `folder` alone: the tests below differ only in the plugin they put there."""
    return cli_voxelize(
        tetra_obj, out, "-q", "--resolution=8", "--method=hybrid", env={**os.environ, "HYVOX_PLUGIN_DIR": str(folder)}
    )


def test_a_plugin_that_does_not_load_says_why(cli_voxelize, tetra_obj, tmp_path):
    # A file of the plugin's name that is no shared object: dlopen's own reason is shown.
    folder = tmp_path / "damaged"
    folder.mkdir()
    (folder / "libhyvox_gl_methods.so").write_bytes(b"not a shared object\n" * 64)
    done = hybrid_run_with_plugins_in(cli_voxelize, tetra_obj, tmp_path / "o.vdb", folder)
    assert done.returncode != 0 and not (tmp_path / "o.vdb").exists()
    assert f"needs {folder}/libhyvox_gl_methods.so, which cannot be loaded: " in done.stderr, done.stderr
    assert "invalid ELF header" in done.stderr, done.stderr


def plugin_copy(folder, data):
    folder.mkdir()
    (folder / "libhyvox_gl_methods.so").write_bytes(data)
    return folder


def test_a_plugin_from_another_build_is_refused(cli_voxelize, tetra_obj, tmp_path):
    # The real plugin with one digit of its build id changed: the same code, but another
    # build's id. The unchanged copy beside it shows that the copy itself loads.
    data = (pathlib.Path(hyvox.__file__).parent / "libhyvox_gl_methods.so").read_bytes()
    prefix = b"hyvox-plugin-build-id="
    assert data.count(prefix) == 1
    at = data.index(prefix) + len(prefix)
    own = data[at : at + 32].decode()
    assert len(own) == 32 and all(c in "0123456789abcdef" for c in own), own
    other = ("1" if own[0] != "1" else "2") + own[1:]
    done = hybrid_run_with_plugins_in(cli_voxelize, tetra_obj, tmp_path / "o.vdb", plugin_copy(tmp_path / "same", data))
    assert done.returncode == 0 and (tmp_path / "o.vdb").exists(), done.stderr
    (tmp_path / "o.vdb").unlink()

    folder = plugin_copy(tmp_path / "other", data[:at] + other.encode() + data[at + 32 :])
    done = hybrid_run_with_plugins_in(cli_voxelize, tetra_obj, tmp_path / "o.vdb", folder)
    assert done.returncode != 0 and not (tmp_path / "o.vdb").exists()
    assert (
        f"the hybrid method needs {folder}/libhyvox_gl_methods.so, which is from another hyvox build "
        f"(hyvox-plugin-build-id={other}; this hyvox is hyvox-plugin-build-id={own}): install hyvox and its "
        "plugins from one build"
    ) in done.stderr, done.stderr


def test_a_shared_library_without_a_build_id_is_no_plugin(cli_voxelize, tetra_obj, tmp_path):
    # libtbb (loaded with the module here): a shared object that loads, but no hyvox plugin.
    with open("/proc/self/maps") as maps:
        tbb = next(line.split()[5] for line in maps if len(line.split()) >= 6 and "/libtbb.so" in line.split()[5])
    folder = plugin_copy(tmp_path / "tbb", pathlib.Path(tbb).read_bytes())
    done = hybrid_run_with_plugins_in(cli_voxelize, tetra_obj, tmp_path / "o.vdb", folder)
    assert done.returncode != 0 and not (tmp_path / "o.vdb").exists()
    assert (
        f"the hybrid method needs {folder}/libhyvox_gl_methods.so, which has no hyvox build id (not a hyvox plugin)"
    ) in done.stderr, done.stderr


def test_a_reader_program_that_does_not_start_says_why(cli_voxelize, tetrahedron, tmp_path):
    folder = tmp_path / "damaged"
    folder.mkdir()
    reader = folder / "hyvox_assimp_reader"
    model = tetra_3mf(tmp_path / "tetra.3mf", *tetrahedron)
    env = {**os.environ, "HYVOX_PLUGIN_DIR": str(folder)}
    for mode, reason in ((0o755, "Exec format error"), (0o644, "not executable, and not an ELF program")):
        reader.write_bytes(b"not a program\n" * 64)
        reader.chmod(mode)
        done = cli_voxelize(model, tmp_path / "o.vdb", "-q", "--resolution=8", env=env)
        assert done.returncode != 0 and not (tmp_path / "o.vdb").exists()
        assert f"reading '{model}' needs the assimp reader process: cannot start {reader}" in done.stderr, done.stderr
        assert reason in done.stderr, done.stderr


def test_a_reader_program_without_its_execute_bit_still_reads(cli_voxelize, tetrahedron, tmp_path):
    # A zip (the legacy add-on, Blender's extension and wheel installs) keeps no file modes:
    # the program is then started through the program interpreter its ELF header names.
    built = pathlib.Path(hyvox.__file__).parent / "hyvox_assimp_reader"
    folder = tmp_path / "unzipped"
    folder.mkdir()
    (folder / "hyvox_assimp_reader").write_bytes(built.read_bytes())
    (folder / "hyvox_assimp_reader").chmod(0o644)
    assert not os.access(folder / "hyvox_assimp_reader", os.X_OK)
    model = tetra_3mf(tmp_path / "tetra.3mf", *tetrahedron)
    done = cli_voxelize(
        model, tmp_path / "o.vdb", "-q", "--resolution=16", env={**os.environ, "HYVOX_PLUGIN_DIR": str(folder)}
    )
    assert done.returncode == 0, done.stderr
    assert voxels_of(tmp_path / "o.vdb")
