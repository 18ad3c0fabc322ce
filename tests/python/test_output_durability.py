# SPDX-License-Identifier: GPL-3.0-or-later
# The durable_write option, observed in the system calls themselves (strace, an independent
# witness): off (the default), an output file is written to a temporary and renamed, and
# nothing is synced; on, the temporary is fsync'ed before the rename and its folder after it.
# The atomicity itself (no half-written file) is tested in test_vdb_output.py and test_io_vdb.
import os
import re
import shutil
import subprocess
import sys

import pytest

import hyvox

STRACE = shutil.which("strace")


def traced(command, tmp_path, env=None):
    """The fsync and rename calls `command` makes, as (call, paths) in order: paths are the
    file names strace -y shows for a descriptor, or the rename's two arguments."""
    if STRACE is None:
        pytest.fail("strace not found (scripts/install_deps.sh installs it)")
    log = tmp_path / "strace.log"
    done = subprocess.run(
        [STRACE, "-f", "-y", "-qq", "-e", "trace=fsync,fdatasync,rename,renameat,renameat2", "-o", str(log), *command],
        capture_output=True,
        text=True,
        timeout=300,
        env=env,
    )
    assert done.returncode == 0, done.stderr
    calls = []
    for line in log.read_text().splitlines():
        match = re.search(r"\b(fsync|fdatasync|rename|renameat2?)\((.*)\)\s+= 0", line)
        if match:
            calls.append((match.group(1), re.findall(r'<([^>]*)>|"([^"]*)"', match.group(2))))
    return [(call, [a or b for a, b in paths]) for call, paths in calls]


def writes_of(calls, name):
    """The calls that concern output `name`: its temporary's fsync, the rename, the folder's fsync."""
    renames = [
        i for i, (call, paths) in enumerate(calls) if call.startswith("rename") and os.path.basename(paths[-1]) == name
    ]
    assert len(renames) == 1, calls
    at = renames[0]
    temporary = calls[at][1][0]
    assert os.path.basename(temporary).startswith(f".{name}.tmp-"), calls
    synced_before = [paths[0] for call, paths in calls[:at] if call in ("fsync", "fdatasync")]
    synced_after = [paths[0] for call, paths in calls[at + 1 :] if call in ("fsync", "fdatasync")]
    return temporary, synced_before, synced_after


@pytest.mark.parametrize("durable", [False, True], ids=["default", "durable_write"])
def test_cli_syncs_outputs_only_when_asked(durable, cli, tetra_obj, tmp_path):
    folder = tmp_path / "out"
    folder.mkdir()
    command = [
        str(cli),
        "voxelize",
        str(tetra_obj),
        "-o",
        str(folder / "t.vdb"),
        "--stats-json",
        str(folder / "t.json"),
        "-q",
        "--resolution=8",
    ] + (["--durable-write"] if durable else [])
    calls = traced(command, tmp_path)
    for name in ("t.vdb", "t.json"):
        temporary, before, after = writes_of(calls, name)
        if durable:
            assert os.path.realpath(temporary) in [os.path.realpath(p) for p in before], calls
            assert str(folder.resolve()) in [os.path.realpath(p) for p in after], calls
        else:
            assert not any(c in ("fsync", "fdatasync") for c, _ in calls), calls
        assert (folder / name).stat().st_size > 0
    assert sorted(os.listdir(folder)) == ["t.json", "t.vdb"]  # no temporary left


@pytest.mark.parametrize("durable", [False, True], ids=["default", "durable_write"])
def test_module_write_vdb_follows_the_option(durable, tmp_path):
    script = (
        "import sys, hyvox\n"
        "v = [[0.,0,0],[1.,0,0],[0.,1,0],[0.,0,1]]; t = [[0,2,1],[0,1,3],[0,3,2],[1,2,3]]\n"
        f"hyvox.voxelize(v, t, resolution=8).write_vdb(sys.argv[1], durable_write={durable})\n"
    )
    calls = traced(
        [sys.executable, "-c", script, str(tmp_path / "m.vdb")],
        tmp_path,
        env={**os.environ, "PYTHONPATH": os.path.dirname(os.path.dirname(hyvox.__file__))},
    )
    temporary, before, after = writes_of(calls, "m.vdb")
    if durable:
        assert os.path.realpath(temporary) in [os.path.realpath(p) for p in before], calls
        assert str(tmp_path.resolve()) in [os.path.realpath(p) for p in after], calls
    else:
        assert not before and not after, calls


def test_durable_write_is_an_option_of_the_write_not_of_the_voxelization(tetrahedron, tmp_path):
    vertices, triangles = tetrahedron
    assert [spec.name for spec in hyvox.WRITE_OPTIONS] == ["threads", "memory_budget_mib", "durable_write"]
    assert "durable_write" not in [spec.name for spec in hyvox.OPTIONS]
    assert hyvox.option("durable_write").default is False
    grid = hyvox.voxelize(vertices, triangles, resolution=8)
    assert "durable_write" not in grid.stats["options"]  # what decided the voxels only
    with pytest.raises(
        TypeError, match=r"^durable_write is an option of VoxelGrid.write_vdb\(\), not of voxelize\(\)$"
    ):
        hyvox.voxelize(vertices, triangles, resolution=8, durable_write=True)
    with pytest.raises(TypeError, match=r"^resolution is an option of voxelize\(\), not of VoxelGrid.write_vdb\(\)$"):
        grid.write_vdb(tmp_path / "r.vdb", resolution=8)
    # The schema's checks and messages, as for voxelize's options.
    with pytest.raises(TypeError) as error:
        grid.write_vdb(tmp_path / "m.vdb", durable_write="maybe")
    assert str(error.value) == "durable_write must be true or false, got 'maybe'"
    with pytest.raises(ValueError) as error:
        grid.write_vdb(tmp_path / "m.vdb", memory_budget_mib=-1)
    assert str(error.value) == "memory_budget_mib must be a whole number between 0 and 1073741824, got -1"
    assert not (tmp_path / "m.vdb").exists() and not (tmp_path / "r.vdb").exists()
