# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on enables from the build and registers what the artist sees."""

import os

import addon_utils
import bpy

import helpers
from helpers import AddonTestCase


def inside(path, folder):
    return os.path.commonpath([os.path.realpath(path), os.path.realpath(folder)]) == os.path.realpath(folder)


def mapped_libraries():
    """The shared objects this process has mapped, by file name (the kernel's word)."""
    with open("/proc/self/maps") as maps:
        return {os.path.basename(f[5]) for f in (line.split() for line in maps) if len(f) >= 6}


# Read as this file is imported: after the add-on was enabled, before any test here runs.
MAPPED_AFTER_ENABLE = mapped_libraries()


class EnableTest(AddonTestCase):
    def test_enabled_from_build(self):
        enabled, loaded = addon_utils.check(helpers.ADDON_PACKAGE)
        self.assertTrue(enabled and loaded)
        self.assertTrue(
            inside(helpers.addon().__file__, helpers.ADDON_DIR), (helpers.addon().__file__, helpers.ADDON_DIR)
        )

    def test_module_is_the_bundled_one(self):
        # The legacy add-on's own copy, or the extension's wheel (never a module that
        # happens to be on sys.path).
        module = helpers.hyvox_module()
        self.assertTrue(inside(module.__file__, helpers.MODULE_DIR), (module.__file__, helpers.MODULE_DIR))
        self.assertTrue(inside(module._core.__file__, helpers.MODULE_DIR), module._core.__file__)

    def test_enabling_loads_no_gl_plugin(self):
        # Enabling builds the properties from the module's schema (the module is loaded) but
        # asks for no GL device: the GL plugin comes with the first GL run or panel draw.
        self.assertTrue(any(name.startswith("_core") for name in MAPPED_AFTER_ENABLE), sorted(MAPPED_AFTER_ENABLE))
        self.assertFalse("libhyvox_gl_methods.so" in MAPPED_AFTER_ENABLE, "enabling loaded the GL plugin")

    def test_registered(self):
        self.assertTrue(hasattr(bpy.types, "OBJECT_OT_hyvox_voxelize"))
        self.assertTrue(hasattr(bpy.types, "VIEW3D_PT_hyvox_voxelize"))
        self.assertEqual(bpy.types.VIEW3D_PT_hyvox_voxelize.bl_category, "Voxelize")
        self.assertTrue(hasattr(bpy.context.scene, "hyvox"))
        self.assertIn("UNDO", bpy.types.OBJECT_OT_hyvox_voxelize.bl_options)

    def test_module_found(self):
        from helpers import hyvox_module

        module = hyvox_module()
        self.assertTrue(hasattr(module, "voxelize"))

    def test_every_setting_is_described(self):
        settings = bpy.context.scene.hyvox
        for prop in settings.bl_rna.properties:
            if prop.identifier in {"rna_type", "name"}:
                continue
            self.assertTrue(prop.description, prop.identifier)
