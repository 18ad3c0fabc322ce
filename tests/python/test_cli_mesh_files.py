# SPDX-License-Identifier: GPL-3.0-or-later
# Damaged mesh files and dangerous output paths through the command line and
# hyvox.read_mesh (issue 16): a clear error naming the file, exit status 1 or 2, never a
# crash, a hang, a silently different mesh or an overwritten input.
import gzip
import os
import stat
import subprocess

import numpy as np
import pytest

import hyvox


def run(cli, *args):
    return subprocess.run([str(cli), *map(str, args)], capture_output=True, text=True, timeout=300)


HEADER = (
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
)
VERTICES = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
FACES = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"


def bunny_bytes(mesh_dir):
    return (mesh_dir / "bunny_stanford_69k.ply").read_bytes()


def header_end(data):
    return data.index(b"end_header\n") + len(b"end_header\n")


# name, a function of the shared mesh folder giving the file's bytes, and what the message says.
DAMAGED = [
    ("cut_vertices.ply", lambda d: bunny_bytes(d)[: header_end(bunny_bytes(d)) + 1000], "truncated"),
    ("cut_faces.ply", lambda d: bunny_bytes(d)[:-100], "face"),
    ("cut_header.ply", lambda d: bunny_bytes(d)[:100], "end_header"),
    ("no_end_header.ply", lambda d: HEADER.replace("end_header\n", "").encode(), "end_header"),
    ("zero_indices.ply", lambda d: (HEADER + VERTICES + "3 0 2 1\n0\n3 0 3 2\n3 1 2 3\n").encode(), "at least 3"),
    (
        "count_2p64.ply",
        lambda d: (HEADER.replace("vertex 4", "vertex 18446744073709551616") + VERTICES + FACES).encode(),
        "whole number",
    ),
    ("many_faces.ply", lambda d: (HEADER.replace("face 4", "face 100000000") + VERTICES + FACES).encode(), "100000000"),
    ("twelve_faces.ply", lambda d: (HEADER.replace("face 4", "face 12") + VERTICES + FACES[:24]).encode(), "face"),
    ("letters.ply", lambda d: (HEADER + "0 0 0\n1 0 0\n3 a b c\n0 0 1\n" + FACES).encode(), "'a' is not a number"),
    ("no_x.ply", lambda d: (HEADER.replace("float x", "float w") + VERTICES + FACES).encode(), "no 'x'"),
    ("out_of_range.ply", lambda d: (HEADER + VERTICES + "3 0 2 1\n3 0 1 9\n3 0 3 2\n3 1 2 3\n").encode(), "index 9"),
    (
        "cut.ply.gz",
        lambda d: gzip.compress(bunny_bytes(d))[: len(gzip.compress(bunny_bytes(d))) * 85 // 100],
        "ends early",
    ),
    ("two_corners.obj", lambda d: b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "at least 3 corners"),
    ("letters.obj", lambda d: b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 a 3\n", "'a'"),
]


@pytest.mark.parametrize("name,make,message", DAMAGED, ids=[d[0] for d in DAMAGED])
def test_damaged_mesh_is_a_clear_error(cli, mesh_dir, tmp_path, name, make, message):
    mesh = tmp_path / name
    mesh.write_bytes(make(mesh_dir))
    out = tmp_path / "out.vdb"
    result = run(cli, "voxelize", mesh, "-o", out, "--resolution", 32)
    assert result.returncode == 1, (result.returncode, result.stderr)
    assert f"mesh file '{mesh}'" in result.stderr and message in result.stderr, result.stderr
    assert not out.exists()
    # The module raises ValueError; the interpreter lives on.
    with pytest.raises(ValueError, match=message.replace("(", r"\(")):
        hyvox.read_mesh(mesh)


def test_failed_reads_hold_no_memory(tmp_path):
    """The issue's 200-byte PLY declaring 100M faces held 1.5 GB per failed read_mesh."""
    import resource

    mesh = tmp_path / "many.ply"
    mesh.write_text(HEADER.replace("face 4", "face 100000000") + VERTICES + FACES)
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    for _ in range(200):
        with pytest.raises(ValueError, match="100000000"):
            hyvox.read_mesh(mesh)
    assert resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before < 64 * 1024  # KiB


def test_damaged_mesh_in_gamma_sweep(cli, tmp_path):
    mesh = tmp_path / "zero.ply"
    mesh.write_text(HEADER + VERTICES + "3 0 2 1\n0\n3 0 3 2\n3 1 2 3\n")
    result = run(cli, "gamma-sweep", mesh, "--resolution", 16, "--gammas", "1,2")
    assert result.returncode == 1 and "at least 3" in result.stderr, result.stderr


@pytest.mark.parametrize(
    "name",
    [
        "bunny_stanford_69k.ply",
        "spot_vcolor.ply",
        "spot_uv.ply",
        "sponza_crytek_262k_vcolor.ply.gz",
        "dragon_stanford_res2_203k.ply.gz",
    ],
)
def test_read_mesh_matches_numpy_parse(mesh_dir, name):
    """The shared meshes' binary layout read with numpy: the reader returns exactly it."""
    data = (mesh_dir / name).read_bytes()
    if name.endswith(".gz"):
        data = gzip.decompress(data)
    body = header_end(data)
    lines = data[:body].decode().splitlines()
    vertex_count = int(next(line for line in lines if line.startswith("element vertex")).split()[2])
    face_count = int(next(line for line in lines if line.startswith("element face")).split()[2])
    props = [line.split()[1:] for line in lines if line.startswith("property") and "list" not in line]
    kinds = {"float": "<f4", "uchar": "u1"}
    vertex_type = np.dtype([(p[1], kinds[p[0]]) for p in props])
    vertices = np.frombuffer(data, vertex_type, vertex_count, body)
    faces = np.frombuffer(data, np.dtype([("n", "u1"), ("i", "<i4", 3)]), face_count, body + vertices.nbytes)
    assert (faces["n"] == 3).all()

    positions, triangles, attrs = hyvox.read_mesh(mesh_dir / name, attributes=True)
    colors, uvs = attrs.get("colors"), attrs.get("uvs")
    np.testing.assert_array_equal(positions, np.stack([vertices["x"], vertices["y"], vertices["z"]], axis=1))
    np.testing.assert_array_equal(triangles, faces["i"].astype(np.uint32))
    if "red" in vertex_type.names:
        expected = np.stack([vertices[c] / np.float32(255) for c in ("red", "green", "blue")], axis=1)
        np.testing.assert_allclose(colors[:, :3], expected, rtol=0, atol=1e-7)
        assert (colors[:, 3] == 1).all()
    else:
        assert colors is None
    if "s" in vertex_type.names:
        np.testing.assert_array_equal(uvs, np.stack([vertices["s"], vertices["t"]], axis=1))
    else:
        assert uvs is None


@pytest.fixture()
def teapot_copy(mesh_dir, tmp_path):
    mesh = tmp_path / "teapot.ply"
    mesh.write_bytes((mesh_dir / "teapot_utah.ply").read_bytes())
    return mesh


def test_output_that_is_the_input_is_refused(cli, tmp_path, teapot_copy):
    before = teapot_copy.read_bytes()
    (tmp_path / "sub").mkdir()
    os.link(teapot_copy, tmp_path / "hard.ply")
    for out in (teapot_copy, tmp_path / "sub" / ".." / "teapot.ply", tmp_path / "hard.ply"):
        result = run(cli, "voxelize", teapot_copy, "-o", out, "--resolution", 16)
        assert result.returncode == 2 and "is the input mesh" in result.stderr, result.stderr
    result = run(cli, "voxelize", teapot_copy, "-o", tmp_path / "o.vdb", "--stats-json", teapot_copy)
    assert result.returncode == 2 and "is the input mesh" in result.stderr, result.stderr
    result = run(cli, "gamma-sweep", teapot_copy, "--stats-json", teapot_copy, "--gammas", "1,2")
    assert result.returncode == 2 and "is the input mesh" in result.stderr, result.stderr
    assert teapot_copy.read_bytes() == before


def test_stats_json_equal_to_output_is_refused(cli, tmp_path, teapot_copy):
    out = tmp_path / "out.vdb"
    out.write_bytes(b"previous")
    result = run(cli, "voxelize", teapot_copy, "-o", out, "--stats-json", tmp_path / "." / "out.vdb")
    assert result.returncode == 2 and "are the same file" in result.stderr, result.stderr
    assert out.read_bytes() == b"previous"
    new = tmp_path / "new.vdb"  # the same when neither exists yet
    result = run(cli, "voxelize", teapot_copy, "-o", new, "--stats-json", new)
    assert result.returncode == 2 and not new.exists()


def test_non_regular_outputs_are_refused(cli, tmp_path, teapot_copy):
    fifo = tmp_path / "pipe.vdb"
    os.mkfifo(fifo)
    targets = [fifo, tmp_path]
    if os.geteuid() == 0:  # root may make a device node (a copy of /dev/null) to try it on
        device = tmp_path / "null.vdb"
        os.mknod(device, 0o666 | stat.S_IFCHR, os.makedev(1, 3))
        targets.append(device)
    for out in targets:
        for args in (["-o", out], ["-o", tmp_path / "ok.vdb", "--stats-json", out]):
            result = run(cli, "voxelize", teapot_copy, *args, "--resolution", 16)
            assert result.returncode == 1, (out, result.stderr)
            assert "not a regular file" in result.stderr or "is a folder" in result.stderr, result.stderr
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)
    if os.geteuid() == 0:
        assert stat.S_ISCHR(os.lstat(tmp_path / "null.vdb").st_mode)
    assert not (tmp_path / "ok.vdb").exists()
    # The module's writer refuses too.
    grid = hyvox.voxelize(*hyvox.read_mesh(teapot_copy), resolution=16)
    with pytest.raises(ValueError, match="not a regular file"):
        grid.write_vdb(str(fifo))


def test_symlinks_are_followed_and_modes_kept(cli, tmp_path, teapot_copy):
    target = tmp_path / "target.vdb"
    target.write_bytes(b"previous")
    target.chmod(0o640)
    stats = tmp_path / "stats.json"
    stats.write_text("{}")
    stats.chmod(0o600)
    link = tmp_path / "link.vdb"
    link.symlink_to(target)
    result = run(cli, "voxelize", teapot_copy, "-o", link, "--stats-json", stats, "--resolution", 16, "-q")
    assert result.returncode == 0, result.stderr
    assert link.is_symlink() and os.readlink(link) == str(target)  # the link stays, the file it names is new
    assert target.read_bytes() != b"previous" and target.stat().st_size > 100
    assert stat.S_IMODE(target.stat().st_mode) == 0o640 and stat.S_IMODE(stats.stat().st_mode) == 0o600
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.vdb", "stats.json", "target.vdb", "teapot.ply"]
    dangling = tmp_path / "dangling.vdb"
    dangling.symlink_to(tmp_path / "nothing.vdb")
    result = run(cli, "voxelize", teapot_copy, "-o", dangling, "--resolution", 16)
    assert result.returncode == 1 and "symlink to nothing" in result.stderr, result.stderr
    assert not (tmp_path / "nothing.vdb").exists()
