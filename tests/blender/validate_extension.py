# SPDX-License-Identifier: GPL-3.0-or-later
"""Blender's own extension validator (the one `blender --command extension validate`
runs, shipped inside the bpy module) accepts the built extension zip (or
$HYVOX_EXTENSION_ZIP: a release's):
    B/venv/bpyXY/bin/python validate_extension.py BUILD_DIR"""

import glob
import importlib.util
import os
import subprocess
import sys


def main(build_dir):
    given = os.environ.get("HYVOX_EXTENSION_ZIP")
    (zip_path,) = [given] if given else glob.glob(os.path.join(build_dir, "hyvox_blender-*-linux_x64.zip"))
    bpy_dir = os.path.dirname(importlib.util.find_spec("bpy").origin)  # without starting Blender
    (tool,) = glob.glob(os.path.join(bpy_dir, "*", "scripts", "addons_core", "bl_pkg", "cli", "blender_ext.py"))
    run = subprocess.run([sys.executable, tool, "validate", zip_path], capture_output=True, text=True, timeout=120)
    print(run.stdout + run.stderr)
    if run.returncode != 0 or "Success" not in run.stdout:
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
