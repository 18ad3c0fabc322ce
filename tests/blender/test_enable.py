# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on enables from the build and registers what the artist sees."""
import addon_utils
import bpy

from helpers import AddonTestCase


class EnableTest(AddonTestCase):
    def test_enabled_from_build(self):
        enabled, loaded = addon_utils.check("hyvox_blender")
        self.assertTrue(enabled and loaded)
        import hyvox_blender
        self.assertIn("addon", hyvox_blender.__file__)

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
