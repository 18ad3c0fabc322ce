# SPDX-License-Identifier: GPL-3.0-or-later
# Every format hyvox reads (docs/mesh-formats.md), written from the shared meshes by
# mesh_writers.py (from the format descriptions, not by the library that reads them): the
# module and the CLI read back the triangles of the PLY they were written from, plain and
# gzipped. The assimp reader process: held to the memory budget, ended by a cancel, and
# leaving no process behind. A slice of the damage run (tests/damage/damage_meshes.py): a few
# damaged files of every format through the CLI, the module and gamma-sweep.
import gzip
import io
import json
import os
import pathlib
import random
import subprocess
import sys
import threading
import zipfile

import numpy as np
import pytest

import hyvox
import mesh_writers

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "damage"))
import mesh_damage  # noqa: E402

MESHES = ("teapot_utah.ply", "spot_uv.ply")


def corner_rows(vertices, triangles):
    return np.asarray(vertices, np.float32)[np.asarray(triangles, np.int64)].reshape(-1, 9)


def same_triangles(a, b):
    """The same triangles, in any order and through any vertex numbering."""
    return a.shape == b.shape and np.array_equal(a[np.lexsort(a.T[::-1])], b[np.lexsort(b.T[::-1])])


def all_children():
    """This process's child processes: {pid: its /proc stat line}."""
    me = str(os.getpid())
    found = {}
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            stat = open(f"/proc/{pid}/stat").read()
        except OSError:
            continue
        if stat[stat.rindex(")") + 2 :].split()[1] == me:
            found[pid] = stat
    return found


# Children other tests of the session started and keep (a module door's interpreter, say):
# not the reads'.
_EARLIER = {}


@pytest.fixture(autouse=True)
def _earlier_children():
    _EARLIER.clear()
    _EARLIER.update(all_children())


def children():
    """This process's child processes started during the test (none may outlive a read)."""
    return [stat for pid, stat in all_children().items() if pid not in _EARLIER]


@pytest.mark.parametrize("mesh", MESHES)
def test_every_format_reads_back_the_mesh_it_was_written_from(mesh, mesh_dir, cli, tmp_path):
    vertices, triangles = hyvox.read_mesh(mesh_dir / mesh)
    expected = corner_rows(vertices, triangles)
    cpu = hyvox.voxelize(vertices, triangles, resolution=24, method="cpu")
    for name, (suffix, writer) in mesh_writers.FORMATS.items():
        data = writer(vertices, triangles)
        path = tmp_path / f"{name}{suffix}"
        path.write_bytes(data)
        zipped = tmp_path / f"{name}{suffix}.gz"
        zipped.write_bytes(gzip.compress(data))
        for file in (path, zipped):
            v, t = hyvox.read_mesh(file)
            assert same_triangles(corner_rows(v, t), expected), file
            out = tmp_path / "o.vdb"
            done = subprocess.run(
                [
                    str(cli),
                    "voxelize",
                    str(file),
                    "-o",
                    str(out),
                    "-q",
                    "--resolution=24",
                    "--method=cpu",
                    "--stats-json",
                    str(tmp_path / "s.json"),
                ],
                capture_output=True,
                text=True,
                timeout=120,
            )
            assert done.returncode == 0, done.stderr
            assert json.loads((tmp_path / "s.json").read_text())["voxel_count"] == cpu.voxel_count, file
    assert children() == []


def zip_bomb_3mf():
    """A 3MF whose model inflates to 512 MiB of spaces (about 500 KiB on disk)."""
    model = io.BytesIO()
    with zipfile.ZipFile(model, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr(
            "[Content_Types].xml",
            '<?xml version="1.0"?><Types xmlns="http://schemas.openxmlformats.org/'
            'package/2006/content-types"><Default Extension="model" ContentType="application/'
            'vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>',
        )
        z.writestr(
            "_rels/.rels",
            '<?xml version="1.0"?><Relationships xmlns="http://schemas.openxmlformats.org/'
            'package/2006/relationships"><Relationship Target="/3D/3dmodel.model" Id="r" Type="http://'
            'schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>',
        )
        with z.open("3D/3dmodel.model", "w", force_zip64=True) as entry:
            spaces = b" " * (1 << 20)
            for _ in range(512):
                entry.write(spaces)
    return model.getvalue()


def test_the_assimp_process_is_held_to_the_memory_budget(cli, tmp_path):
    bomb = tmp_path / "bomb.3mf"
    bomb.write_bytes(zip_bomb_3mf())
    message = "reading it through assimp needs more than the memory budget of 256 MiB (memory_budget_mib)"
    with pytest.raises(ValueError, match=r"bomb\.3mf.*" + message.replace("(", r"\(").replace(")", r"\)")):
        hyvox.read_mesh(bomb, memory_budget_mib=256)
    done = subprocess.run(
        [str(cli), "voxelize", str(bomb), "-o", str(tmp_path / "o.vdb"), "-q", "--memory-budget-mib=256"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 1 and message in done.stderr, done.stderr
    assert children() == []


def test_a_cancel_ends_the_assimp_process(mesh_dir, tmp_path):
    # The dragon as FBX (about 60 MB): long enough to read that a cancel lands during it.
    vertices, triangles = hyvox.read_mesh(mesh_dir / "dragon_stanford_871k.ply.gz")
    path = tmp_path / "dragon.fbx"
    path.write_bytes(mesh_writers.fbx(vertices, triangles))
    token = hyvox.CancelToken()
    started = threading.Event()
    outcome = {}

    def read():
        started.set()
        try:
            hyvox.read_mesh(path, cancel=token)
            outcome["read"] = True
        except hyvox.Cancelled:
            outcome["cancelled"] = True

    reader = threading.Thread(target=read)
    reader.start()
    started.wait()
    # The cancel lands while the reader process runs: once it is there (it has no event to
    # wait on; the check of the 60 MB first takes tens of milliseconds).
    while not children() and reader.is_alive():
        os.sched_yield()
    assert children(), "the read ended before its process was seen"
    token.cancel()
    reader.join(timeout=120)
    assert not reader.is_alive()
    assert outcome == {"cancelled": True}
    assert children() == []


def test_a_format_hyvox_does_not_read_is_refused_naming_those_it_reads(tmp_path):
    for name in ("scene.blend", "model.dae", "model.3ds", "mesh"):
        (tmp_path / name).write_bytes(b"not read")
        with pytest.raises(ValueError, match="hyvox reads .ply, .obj, .stl, .off, .gltf, .glb, .fbx, .3mf files"):
            hyvox.read_mesh(tmp_path / name)


def test_damaged_files_of_every_format_end_the_same_way_through_every_door(mesh_dir, cli, tmp_path):
    """The damage run's slice: the teapot in every format, three damaged files of each kind."""
    module = mesh_damage.ModuleDoor(os.environ.get("PYTHONPATH", ""))
    vertices, triangles = hyvox.read_mesh(mesh_dir / "teapot_utah.ply")
    problems, seen = [], {}
    try:
        for name, (suffix, writer) in mesh_writers.FORMATS.items():
            original = tmp_path / f"teapot{suffix}"
            data = writer(vertices, triangles)
            original.write_bytes(data)
            whole = module(str(original))
            assert whole["outcome"] == "ok", whole
            rng = random.Random(f"slice {name}")
            for k in range(12):
                kind = mesh_damage.KINDS[k % 4]
                damaged, note = mesh_damage.damaged(name, data, vertices, triangles, kind, rng)
                if damaged is None:
                    continue
                path = tmp_path / f"damaged{suffix}"
                path.write_bytes(damaged)
                outcomes = (
                    mesh_damage.cli_door(str(cli), str(path), str(tmp_path)),
                    module(str(path), str(original) if kind == "truncate" and name == "obj" else None),
                    mesh_damage.gamma_sweep_door(str(cli), str(path), str(tmp_path)),
                )
                seen[outcomes[0]["outcome"]] = seen.get(outcomes[0]["outcome"], 0) + 1
                found = mesh_damage.judge(name, kind, note, whole, *outcomes)
                if found:
                    problems.append((name, kind, note, found))
    finally:
        module.close()
    assert problems == []
    assert seen.get("error", 0) > 0 and seen.get("ok", 0) > 0  # both outcomes were met
