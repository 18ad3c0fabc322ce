# SPDX-License-Identifier: GPL-3.0-or-later
"""The self-contained wheel installs into a clean venv and works there on its own:
    python3 check_installed_wheel.py BUILD_DIR VENV MESH [WHEEL]
(Debian's python3: it has pyopenvdb and the build tree's hyvox to compare with.)

- the wheel (WHEEL, else the build tree's B/wheel/hyvox-*.whl) is tagged for VENV's Python
  manylinux x86_64 and bundles no part of the GL driver stack. The build tree's wheel has the
  machine's libraries grafted in (hyvox.libs/, one Debian copyright file each); a release
  wheel (scripts/build_release.sh) has them linked in and carries the licence text of each
  one that scripts/release/licences.txt names;
- pip installs it into VENV (numpy only, no system site-packages) without the network;
- in a process started with an empty environment (no LD_LIBRARY_PATH, no PYTHONPATH),
  `import hyvox` + a CPU voxelization map only libraries from the installed wheel plus
  the base system ones every manylinux wheel may use (/proc/self/maps), and none of the
  plugins (native/src/core/plugin_library.h); a GL method loads the wheel's GL plugin,
  takes libEGL from the system and sets the same voxels as the CPU method; a 3MF file is
  read by the wheel's assimp reader process (found in the wheel: the environment is empty
  and the wheel's binaries know no build folder) and loads no assimp into the caller;
- its voxels equal the build tree's module's; the `hyvox` command writes a .vdb that
  pyopenvdb reads back as the same voxels; ldd finds every library of the installed CLI
  binary and of the plugins inside the wheel or in that base set (libEGL: the system's),
  and of the assimp reader program, and the installed CLI finds the plugin and the reader
  (a 3MF file, a GL method)."""

import glob
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest
import zipfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
BUILD_DIR, VENV, MESH = sys.argv[1:4] if len(sys.argv) >= 4 else ("", "", "")
WHEEL = sys.argv[4] if len(sys.argv) >= 5 else ""
RELEASE_LICENCES = os.path.join(HERE, "..", "..", "scripts", "release", "licences.txt")
# The GL driver stack (glvnd): always the machine's own, never in the wheel.
GL_STACK = ("libEGL.so", "libGL.so", "libOpenGL.so", "libGLX.so", "libGLdispatch.so")
# What a manylinux wheel may take from the system (auditwheel's policy) and this one needs.
BASE_SYSTEM = (
    "libc.so.6",
    "libm.so.6",
    "libdl.so.2",
    "librt.so.1",
    "libpthread.so.0",
    "libstdc++.so.6",
    "libgcc_s.so.1",
    "libz.so.1",
    "ld-linux-x86-64.so.2",
    "linux-vdso.so.1",
)


def soname_of(path):
    """libfoo.so.1.2.3 -> libfoo.so.1 (what BASE_SYSTEM names); ld-linux kept whole."""
    name = os.path.basename(path)
    match = re.match(r"(.+?\.so(?:\.\d+)?)", name)
    return match.group(1) if match else name


def run(command, **kw):
    return subprocess.run(command, check=True, capture_output=True, text=True, timeout=300, **kw)


class InstalledWheelTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        (cls.wheel,) = [WHEEL] if WHEEL else glob.glob(os.path.join(BUILD_DIR, "wheel", "hyvox-*.whl"))
        with zipfile.ZipFile(cls.wheel) as whl:
            cls.grafted = any(n.startswith("hyvox.libs/") for n in whl.namelist())
        cls.python = os.path.join(VENV, "bin", "python")
        run(
            [
                cls.python,
                "-m",
                "pip",
                "install",
                "--disable-pip-version-check",
                "--no-index",
                "--no-deps",
                "--force-reinstall",
                "-q",
                cls.wheel,
            ]
        )
        cls.site = run(
            [cls.python, "-c", "import sysconfig; print(sysconfig.get_paths()['platlib'])"],
            env={"PATH": "/usr/bin:/bin"},
        ).stdout.strip()
        cls.tmp = tempfile.TemporaryDirectory(prefix="hyvox-wheel-")
        # An empty environment: nothing points the loader or Python at the build or -dev files.
        cls.clean_env = {"PATH": os.path.join(VENV, "bin") + ":/usr/bin:/bin", "HOME": cls.tmp.name}
        run([cls.python, os.path.join(HERE, "wheel_child.py"), MESH, cls.tmp.name], env=cls.clean_env)
        with open(os.path.join(cls.tmp.name, "child.json")) as f:
            cls.child = json.load(f)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def in_wheel(self, path):
        return any(
            os.path.realpath(path).startswith(os.path.realpath(os.path.join(self.site, d)) + os.sep)
            for d in ("hyvox", "hyvox.libs")
        )

    def test_tags_contents_and_licences(self):
        cp = run([self.python, "-c", 'import sys; print("cp%d%d" % sys.version_info[:2])']).stdout.strip()
        self.assertRegex(
            os.path.basename(self.wheel),
            rf"^hyvox-[\d.]+-{cp}-{cp}-manylinux_2_\d+_x86_64(\.manylinux_2_\d+_x86_64)*\.whl$",
        )
        with zipfile.ZipFile(self.wheel) as whl:
            names = whl.namelist()
        self.assertIn("hyvox/bin/hyvox", names)
        bundled = [n for n in names if n.startswith("hyvox.libs/")]
        for stack in GL_STACK:
            self.assertFalse(
                [n for n in bundled if os.path.basename(n).startswith(stack.split(".")[0] + "-")],
                f"{stack} must not be bundled",
            )
        if self.grafted:
            self.check_grafted_libraries(names, bundled)
        else:
            with open(RELEASE_LICENCES) as f:
                wanted = [line.split()[0] for line in f if line.strip() and not line.startswith("#")]
            texts = sorted(os.path.basename(n)[:-4] for n in names if re.search(r"licenses/bundled/[^/]+\.txt$", n))
            self.assertEqual(texts, sorted(wanted))

    def check_grafted_libraries(self, names, bundled):
        with zipfile.ZipFile(self.wheel) as whl:
            record = [n for n in names if n.endswith("licenses/bundled/LIBRARIES")]
            self.assertEqual(len(record), 1, names)
            listed = whl.read(record[0]).decode().split("\n")
        # Every library the build tree's module takes from this machine (ldd), other than
        # the base system and the GL stack, is bundled.
        (core,) = glob.glob(os.path.join(BUILD_DIR, "python", "hyvox", "_core*.so"))
        needed = [line.split()[0] for line in run(["ldd", core]).stdout.splitlines() if "=>" in line]
        needed = [n for n in needed if soname_of(n) not in BASE_SYSTEM and not n.startswith(GL_STACK)]
        self.assertTrue(needed)
        for name in needed:
            # auditwheel puts -<hash> before the first dot of the file name:
            # liblog4cplus-2.0.so.3 -> liblog4cplus-2-3cd2169a.0.so.3.4.7
            stem = name.split(".")[0]
            self.assertTrue([n for n in bundled if os.path.basename(n).startswith(stem + "-")], name)
        listed = [line for line in listed if line.strip()]
        self.assertEqual(len(listed), len(bundled), listed)
        for line in listed:
            package = line.split()[1]
            self.assertIn(f"licenses/bundled/{package}.copyright", "\n".join(names))

    def test_import_and_cpu_use_only_the_wheel(self):
        self.assertTrue(self.in_wheel(self.child["core_file"]), self.child["core_file"])
        outside = [
            p
            for p in self.child["loaded_by_import_and_cpu"]
            if not self.in_wheel(p) and soname_of(p) not in BASE_SYSTEM
        ]
        self.assertEqual(outside, [], "libraries loaded from outside the wheel")
        if self.grafted:
            self.assertTrue(any("/hyvox.libs/libtbb-" in p for p in self.child["loaded_by_import_and_cpu"]))
        plugins = [
            p for p in self.child["loaded_by_import_and_cpu"] if re.search(r"/(libhyvox_|libassimp|libepoxy|libEGL)", p)
        ]
        self.assertEqual(plugins, [], "a cpu run loaded a plugin or what it brings")

    def test_plugins_load_from_the_wheel_when_needed(self):
        def loaded(step, prefix):
            return [p for p in self.child[step] if os.path.basename(p).startswith(prefix)]

        (gl_plugin,) = loaded("loaded_by_gl", "libhyvox_gl_methods.so")
        self.assertTrue(self.in_wheel(gl_plugin), gl_plugin)
        self.assertTrue(all(self.in_wheel(p) for p in loaded("loaded_by_gl", "libepoxy")), self.child["loaded_by_gl"])
        # assimp runs in the reader process: nothing of it is mapped into the caller.
        self.assertEqual(loaded("loaded_by_3mf", "libassimp"), [], self.child["loaded_by_3mf"])
        self.assertEqual(self.child["model_triangles"], 1)

    def test_gl_driver_from_the_system(self):
        egl = [p for p in self.child["loaded_by_gl"] if os.path.basename(p).startswith("libEGL.so")]
        self.assertEqual(len(egl), 1, self.child["loaded_by_gl"])
        self.assertFalse(self.in_wheel(egl[0]))
        self.assertGreater(self.child["gl_voxels"], 0)
        self.assertTrue(self.child["gl_equals_cpu"], "the GL method's voxels differ from the cpu method's")

    def test_voxels_equal_the_build_tree_module(self):
        got = np.load(os.path.join(self.tmp.name, "cpu_coords.npy"))
        sys.path.insert(0, os.path.join(BUILD_DIR, "python"))
        import hyvox  # the build tree's (Debian's python, PYTHONPATH-free import)

        vertices, triangles = hyvox.read_mesh(MESH)
        expected = hyvox.voxelize(vertices, triangles, resolution=128, method="cpu")
        np.testing.assert_array_equal(
            np.sort(got.view("i4,i4,i4"), axis=0), np.sort(expected.coords().view("i4,i4,i4"), axis=0)
        )
        self.assertEqual(self.child["voxel_size"], expected.voxel_size)

    def test_cli_writes_the_same_voxels(self):
        out = os.path.join(self.tmp.name, "bunny.vdb")
        run(
            [os.path.join(VENV, "bin", "hyvox"), "voxelize", MESH, "-o", out, "--resolution", "128", "--method", "cpu"],
            env=self.clean_env,
        )
        sys.path.insert(0, os.path.join(HERE, "..", "blender"))
        import vdb_dump  # pyopenvdb: an independent reader of the file

        coords, size, zero, _ = vdb_dump.read(out)
        centres = zero + coords * size
        expected = (
            np.asarray(self.child["origin"])
            + (np.load(os.path.join(self.tmp.name, "cpu_coords.npy")) + 0.5) * self.child["voxel_size"]
        )
        self.assertEqual(len(centres), len(expected))
        key = lambda a: a[np.lexsort(np.round(a, 6).T[::-1])]
        np.testing.assert_allclose(key(centres), key(expected), atol=1e-6 * self.child["voxel_size"])

    def test_cli_binary_and_plugin_libraries(self):
        plugins = sorted(glob.glob(os.path.join(self.site, "hyvox", "libhyvox_*.so")))
        self.assertEqual([os.path.basename(p) for p in plugins], ["libhyvox_gl_methods.so"])
        reader = os.path.join(self.site, "hyvox", "hyvox_assimp_reader")
        self.assertTrue(os.access(reader, os.X_OK), reader)
        for binary in [os.path.join(self.site, "hyvox", "bin", "hyvox"), reader] + plugins:
            lines = run(["ldd", binary], env=self.clean_env).stdout.splitlines()
            self.assertFalse([line for line in lines if "not found" in line], lines)
            for line in lines:
                parts = line.split()
                path = parts[2] if "=>" in parts and len(parts) > 2 else parts[0]
                if self.in_wheel(path) or soname_of(path) in BASE_SYSTEM or os.path.basename(path).startswith(GL_STACK):
                    continue
                self.fail(f"{binary} resolves {line.strip()} outside the wheel")

    def test_installed_cli_finds_the_plugins(self):
        model = os.path.join(self.tmp.name, "triangle.3mf")  # written by wheel_child.py
        for args in ([model], [MESH, "--method", "hybrid"]):
            out = os.path.join(self.tmp.name, "plugin.vdb")
            run(
                [os.path.join(VENV, "bin", "hyvox"), "voxelize", *args, "-o", out, "-q", "--resolution", "32"],
                env=self.clean_env,
            )
            self.assertGreater(os.path.getsize(out), 0)
            os.remove(out)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
