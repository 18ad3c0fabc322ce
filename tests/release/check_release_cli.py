# SPDX-License-Identifier: GPL-3.0-or-later
"""The standalone command of hyvox-VERSION-linux-x64-cli.zip, unpacked anywhere (here: a
folder whose path has a space and non-ASCII letters), voxelizes the shared meshes exactly as
the build tree's hyvox does:
    python3 check_release_cli.py BUILD_DIR CLI_ZIP MESH_DIR
(Debian's python3: pyopenvdb reads both files.) For every shared mesh, the cpu method in
surface and solid mode at 128 and 256 voxels, and with colours and normals where the mesh has
them: the two files hold the same grids with the same transform, the same active voxels and
the same values. The GL plugin and the mesh reader program come from the archive too: a GL
method run and a 3MF file read by it, with an empty environment."""

import glob
import os
import subprocess
import sys
import tempfile
import unittest
import zipfile

import numpy as np
import pyopenvdb as vdb

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import mesh_writers  # noqa: E402  (numpy and the standard library only)

BUILD_DIR, CLI_ZIP, MESH_DIR = sys.argv[1:4] if len(sys.argv) >= 4 else ("", "", "")
MESHES = sorted(glob.glob(os.path.join(MESH_DIR, "*.ply")) + glob.glob(os.path.join(MESH_DIR, "*.ply.gz")))
# Meshes with colour (vertex colours or UVs and a texture) and the attribute options for them.
ATTRIBUTES = {
    "sponza_crytek_262k_vcolor.ply.gz": ["--attributes", "color,normal"],
    "spot_vcolor.ply": ["--attributes", "color,normal"],
    "spot_uv.ply": ["--attributes", "color,normal", "--texture", os.path.join(MESH_DIR, "spot_texture.png")],
}


def grids_of(path):
    """{name: (class, transform's voxel size and origin, active count, dense array of the active
    voxels' bounding box, its origin)} of every grid in the file."""
    out = {}
    for meta in vdb.readAllGridMetadata(path):
        grid = vdb.read(path, meta.name)
        lo, hi = grid.evalActiveVoxelBoundingBox()
        shape = tuple(high - low + 1 for low, high in zip(lo, hi))
        if grid.valueTypeName.startswith("vec3"):
            shape = shape + (3,)
        dense = np.zeros(shape, np.float32)
        grid.copyToArray(dense, ijk=lo)
        transform = (tuple(grid.transform.voxelSize()), tuple(grid.transform.indexToWorld((0, 0, 0))))
        out[meta.name] = (grid.valueTypeName, transform, grid.activeVoxelCount(), dense, tuple(lo))
    return out


def run(command, **kw):
    return subprocess.run(command, check=True, capture_output=True, text=True, timeout=600, **kw)


class ReleaseCliTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="hyvox release é 漢 ")
        with zipfile.ZipFile(CLI_ZIP) as z:
            z.extractall(cls.tmp.name)
            top = {n.split("/")[0] for n in z.namelist()}
        (folder,) = top
        cls.cli = os.path.join(cls.tmp.name, folder, "hyvox")
        for program in (cls.cli, os.path.join(cls.tmp.name, folder, "hyvox_assimp_reader")):
            os.chmod(program, 0o755)  # zipfile keeps no permissions
        cls.env = {"PATH": "/usr/bin:/bin", "HOME": cls.tmp.name}

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def compare(self, mesh, options):
        ours = os.path.join(self.tmp.name, "release.vdb")
        theirs = os.path.join(self.tmp.name, "build tree.vdb")
        run([self.cli, "voxelize", mesh, "-o", ours, "-q", *options], env=self.env)
        run([os.path.join(BUILD_DIR, "hyvox"), "voxelize", mesh, "-o", theirs, "-q", *options])
        got, expected = grids_of(ours), grids_of(theirs)
        self.assertEqual(sorted(got), sorted(expected))
        for name in expected:
            g, e = got[name], expected[name]
            self.assertEqual(g[:3], e[:3], name)
            self.assertEqual(g[4], e[4], name)
            np.testing.assert_array_equal(g[3], e[3], err_msg=name)
        return expected

    def test_shared_meshes_equal_the_build_tree(self):
        self.assertGreaterEqual(len(MESHES), 10, MESH_DIR)
        for mesh in MESHES:
            name = os.path.basename(mesh)
            for resolution in ("128", "256"):
                for mode in ("conservative", "solid"):
                    with self.subTest(mesh=name, resolution=resolution, mode=mode):
                        grids = self.compare(mesh, ["--method", "cpu", "--mode", mode, "--resolution", resolution])
                        self.assertGreater(grids["density"][2], 0)
            if name in ATTRIBUTES:
                with self.subTest(mesh=name, attributes=True):
                    grids = self.compare(mesh, ["--method", "cpu", "--resolution", "128", *ATTRIBUTES[name]])
                    self.assertIn("color", grids)
                    self.assertIn("normal", grids)

    def test_gl_method_equals_cpu(self):
        mesh = os.path.join(MESH_DIR, "bunny_stanford_69k.ply")
        files = {}
        for method in ("cpu", "hybrid"):
            files[method] = os.path.join(self.tmp.name, f"{method}.vdb")
            run(
                [self.cli, "voxelize", mesh, "-o", files[method], "-q", "--method", method, "--resolution", "96"],
                env=self.env,
            )
        gl, cpu = grids_of(files["hybrid"])["density"], grids_of(files["cpu"])["density"]
        self.assertEqual(gl[:3], cpu[:3])
        np.testing.assert_array_equal(gl[3], cpu[3])

    def test_reader_program_reads_3mf(self):
        # A one-triangle 3MF file: only assimp reads it, in the archive's reader program.
        model = os.path.join(self.tmp.name, "triangle.3mf")
        with open(model, "wb") as f:
            f.write(mesh_writers.three_mf(np.eye(3, dtype=np.float32), np.array([[0, 1, 2]], np.uint32)))
        out = os.path.join(self.tmp.name, "triangle.vdb")
        run([self.cli, "voxelize", model, "-o", out, "-q", "--resolution", "16"], env=self.env)
        self.assertGreater(grids_of(out)["density"][2], 0)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
