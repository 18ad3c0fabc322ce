# SPDX-License-Identifier: GPL-3.0-or-later
# Run: PYTHONPATH=BUILD/python /usr/bin/python3 -m pytest tests/python
# (CTest runs this as the test "pytest"). The CLI is taken from $HYVOX_CLI, else from
# BUILD/hyvox next to BUILD/python; meshes from $HYVOX_MESH_DIR, else ../shared/data/meshes.
import os
import pathlib
import subprocess

import pytest

import hyvox

REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def mesh_dir() -> pathlib.Path:
    path = pathlib.Path(os.environ.get("HYVOX_MESH_DIR", REPO.parent / "shared" / "data" / "meshes"))
    if not (path / "bunny_stanford_69k.ply").exists():
        # A failure, not a skip: a skipped mesh test reads as a pass in CTest's summary.
        pytest.fail(f"shared meshes not found in {path} (set HYVOX_MESH_DIR)")
    return path


@pytest.fixture(scope="session")
def cli() -> pathlib.Path:
    default = pathlib.Path(hyvox.__file__).resolve().parents[2] / "hyvox"
    path = pathlib.Path(os.environ.get("HYVOX_CLI", default))
    if not path.exists():
        pytest.fail(f"hyvox CLI not found at {path} (set HYVOX_CLI)")
    return path


@pytest.fixture(scope="session")
def cli_voxelize(cli):
    """run(mesh, out, *args, timeout=120, **kwargs): `hyvox voxelize MESH -o OUT ARGS...` in a
    child process, its output captured as text, `kwargs` (env, cwd, ...) passed to
    subprocess.run. One way for every test to start the CLI, so that a test names only what
    it varies; the CLI's path is absolute, so a test may run it in another folder (cwd)."""
    program = os.path.abspath(cli)

    def run(mesh, out, *args, timeout=120, **kwargs):
        command = [program, "voxelize", str(mesh), "-o", str(out), *map(str, args)]
        return subprocess.run(command, capture_output=True, text=True, timeout=timeout, **kwargs)

    return run


def shared_mesh(name, file):
    """A session fixture `name`: (vertices, triangles) of the shared mesh `file`."""

    @pytest.fixture(scope="session", name=name)
    def read(mesh_dir):
        return hyvox.read_mesh(mesh_dir / file)

    return read


bunny = shared_mesh("bunny", "bunny_stanford_69k.ply")
dragon = shared_mesh("dragon", "dragon_stanford_871k.ply.gz")
spot = shared_mesh("spot", "spot_vcolor.ply")  # closed
elephant = shared_mesh("elephant", "elephant_holes.ply")  # open: 1353 boundary edges


@pytest.fixture()
def tetrahedron():
    vertices = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    triangles = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    return vertices, triangles


@pytest.fixture()
def tetra_obj(tetrahedron, tmp_path) -> pathlib.Path:
    """The tetrahedron as an OBJ file in tmp_path, for the CLI."""
    vertices, triangles = tetrahedron
    path = tmp_path / "tetra.obj"
    path.write_text(
        "".join(f"v {x:g} {y:g} {z:g}\n" for x, y, z in vertices)
        + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in triangles)
    )
    return path
