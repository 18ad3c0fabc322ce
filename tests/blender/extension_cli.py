# SPDX-License-Identifier: GPL-3.0-or-later
"""The headless entry point of the installed extension (Blender 4.2+, run_bpy_tests.py):
cli_blender.py from the extension's own folder, run in a new Blender process on the user
folder the extension was installed into, must find the add-on under the extension's module
name (bl_ext.user_default.hyvox_blender), enable it there and voxelize the saved scene; the
.vdb holds exactly the module's voxels of the world-space mesh.

The bpy module has no Blender binary, so the child is this venv's Python importing bpy,
opening the .blend and running the script as `blender -b FILE --python SCRIPT -- ARGS` would."""

import json
import os
import subprocess
import sys

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase

# The child: open the .blend, run the script as __main__ with its arguments after `--`,
# then list the hyvox add-on packages imported in that process.
CHILD = """
import os, runpy, sys
blend, script, listing = sys.argv[1:4]
import bpy
bpy.ops.wm.open_mainfile(filepath=blend)
sys.argv = [script, "--"] + sys.argv[4:]
runpy.run_path(script, run_name="__main__")
with open(listing, "w") as f:
    f.write("\\n".join(sorted(m for m in sys.modules if m.split(".")[-1] == "hyvox_blender")))
sys.stdout.flush()
os._exit(0)
"""

LOCATION = (0.5, -0.25, 1.0)


class ExtensionCliTest(AddonTestCase):
    def test_bunny_through_installed_cli(self):
        self.assertTrue(helpers.ADDON_PACKAGE.startswith("bl_ext."), "run by run_bpy_tests.py only")
        script = os.path.join(helpers.ADDON_DIR, "cli_blender.py")
        self.assertTrue(os.path.isfile(script), script)
        bunny = helpers.bunny()
        bunny.location = LOCATION
        blend = os.path.join(self.out, "bunny.blend")
        bpy.ops.wm.save_as_mainfile(filepath=blend, copy=True)
        vdb_dir = os.path.join(self.out, "vdb")
        stats = os.path.join(self.out, "stats.json")
        listing = os.path.join(self.out, "addons.txt")
        # BLENDER_USER_RESOURCES (run_bpy_tests.py) is inherited: the same user folder.
        done = subprocess.run(
            [
                sys.executable,
                "-c",
                CHILD,
                blend,
                script,
                listing,
                "--objects",
                "Bunny",
                "--output",
                vdb_dir,
                "--resolution",
                "64",
                "--method",
                "cpu",
                "--mode",
                "conservative",
                "--stats-json",
                stats,
            ],
            capture_output=True,
            text=True,
            timeout=240,
        )
        self.assertEqual(done.returncode, 0, done.stdout[-3000:] + done.stderr[-3000:])
        with open(listing) as f:
            imported = f.read().split("\n")
        # The extension's package, not a second copy of its files as a legacy add-on.
        self.assertEqual(imported, [helpers.ADDON_PACKAGE])
        self.assertEqual(sorted(os.listdir(vdb_dir)), ["Bunny_voxels.vdb"])
        with open(stats) as f:
            (volume,) = json.load(f)["volumes"]

        vertices, triangles = helpers.bunny_arrays()
        world = np.asarray(vertices, np.float64) + LOCATION
        grid = helpers.hyvox_module().voxelize(world.astype(np.float32), triangles, resolution=64, method="cpu")
        expected = np.asarray(grid.origin) + (grid.coords() + 0.5) * grid.voxel_size
        got = helpers.vdb_world_centres(os.path.join(vdb_dir, "Bunny_voxels.vdb"))
        self.assertEqual(len(got), len(expected))
        np.testing.assert_allclose(
            helpers.sorted_rows(got), helpers.sorted_rows(expected), atol=1e-5 * grid.voxel_size + 1e-6
        )
        print("cli through", helpers.ADDON_PACKAGE, ":", len(got), "voxels; stats", volume.get("voxel_counts"))
