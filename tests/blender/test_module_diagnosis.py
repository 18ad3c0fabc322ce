# SPDX-License-Identifier: GPL-3.0-or-later
"""Enabling an add-on whose compiled module cannot load says why in plain words (which
file, which Python it was built for, which library is missing), in a child Blender
enabling a copy of the add-on with a broken module bundled (tests/python/broken_module.py)."""

import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

import bpy

import helpers
from helpers import AddonTestCase

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
from broken_module import GONE, SUFFIX, build_broken_package  # noqa: E402

ENABLE = """
import sys, addon_utils
sys.path.insert(0, {addon!r})
module = addon_utils.enable("hyvox_blender", default_set=True)
print("ENABLED" if module else "NOT ENABLED")
"""


class ModuleDiagnosisTest(AddonTestCase):
    def test_enable_names_the_missing_library(self):
        with tempfile.TemporaryDirectory(prefix="hyvox-broken-") as tmp:
            root = pathlib.Path(tmp)
            broken = build_broken_package(root)
            addon = root / "addon"
            shutil.copytree(
                helpers.ADDON_DIR, addon / "hyvox_blender", ignore=shutil.ignore_patterns("__pycache__", "hyvox")
            )
            shutil.copytree(broken, addon / "hyvox_blender" / "hyvox")
            run = subprocess.run(
                [
                    bpy.app.binary_path,
                    "-b",
                    "--factory-startup",
                    "-noaudio",
                    "--python-expr",
                    ENABLE.format(addon=str(addon)),
                ],
                capture_output=True,
                text=True,
                timeout=120,
            )
            output = run.stdout + run.stderr
            self.assertIn("NOT ENABLED", output)
            self.assertIn("hyvox could not load its compiled module.", output)
            self.assertIn(f"File: {addon / 'hyvox_blender' / 'hyvox' / ('_core' + SUFFIX)}", output)
            self.assertIn("Built for: Python %d.%d" % sys.version_info[:2], output)
            self.assertIn(f"Missing libraries: {GONE}.", output)
