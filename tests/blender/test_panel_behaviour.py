# SPDX-License-Identifier: GPL-3.0-or-later
"""What the panel and the operator do for the artist: Auto first and the GL methods' device
named under Method, tooltips in plain words first, the scene's frame range by
default, the result selected and visible after a run (the source hidden on request), a
re-run from the selected result, and a status message that says what was made."""

import os

import bpy

import helpers
from helpers import AddonTestCase


class Labels:
    """Enough of a UILayout for a panel's draw(): keeps the labels' texts, ignores the rest."""

    def __init__(self, texts):
        self.__dict__["texts"] = texts

    def label(self, text="", icon="NONE"):
        self.texts.append(text)

    def __getattr__(self, name):  # column(), row(), prop(), operator(), ...
        return lambda *args, **kw: self

    def __setattr__(self, name, value):  # use_property_split, alignment, an operator's properties
        pass


class PanelBehaviourTest(AddonTestCase):
    def test_methods_auto_first_and_the_panel_names_the_gl_device(self):
        # The method list is fixed (enabling asks for no device, test_enable.py); the panel's
        # note under Method says where a GL method runs, from the module's device list.
        from hyvox_blender.blender.ui import panels as ui

        devices = helpers.hyvox_module().gl_devices()
        items = list(bpy.context.scene.hyvox.bl_rna.properties["method"].enum_items)
        self.assertEqual(items[0].identifier, "auto")
        for item in items:
            self.assertEqual(item.icon, "NONE", item.identifier)
            if item.identifier in ("hybrid", "triangle", "fragment", "tessellation"):
                self.assertIn("Needs OpenGL 4.5", item.description)
                self.assertFalse(any(d["name"] in item.description for d in devices), item.description)
        hardware = [d for d in devices if not d["software"]]
        expected = (
            f"GPU: {hardware[0]['name']}"
            if hardware
            else "GL runs in software here (slow)"
            if devices
            else "No OpenGL 4.5 device here"
        )
        settings = bpy.context.scene.hyvox
        settings.method = "hybrid"
        texts = []
        layout = Labels(texts)
        panel = type("Panel", (), {"layout": layout, "layout_split": lambda self: layout})()
        ui.VIEW3D_PT_hyvox_voxelize.draw(panel, bpy.context)
        settings.property_unset("method")
        self.assertIn(expected, texts)

    def test_tooltips_start_in_plain_words(self):
        from hyvox_blender.blender.ui import properties

        scene = bpy.context.scene.hyvox.bl_rna.properties
        prefs = helpers.addon_preferences().bl_rna.properties
        for name, plain in properties.PLAIN_WORDS.items():
            description = (scene[name] if name in scene else prefs[name]).description
            self.assertTrue(description.startswith(plain), description)
            help_text = properties.option_spec(name).help
            self.assertIn(help_text[1:], description)  # the schema's words (and term) follow
            self.assertGreater(description.index(help_text[1:]), len(plain))

    def test_labels_and_tooltips_in_blenders_words(self):
        """Blender's spelling ("Color"), no Markdown in tooltips, and every setting of the
        Scene, the operator and the preferences described (its choices too)."""
        texts = []
        for rna in (
            bpy.context.scene.hyvox.bl_rna,
            bpy.ops.object.hyvox_voxelize.get_rna_type(),
            helpers.addon_preferences().bl_rna,
        ):
            for prop in rna.properties:
                if prop.identifier in ("rna_type", "name", "bl_idname"):
                    continue
                self.assertTrue(prop.description, prop.identifier)
                texts += [prop.name, prop.description]
                if prop.type == "ENUM":
                    texts += [text for item in prop.enum_items for text in (item.name, item.description)]
        for text in texts:
            self.assertNotIn("`", text)
            self.assertNotIn("olour", text)  # Colour, colour
            self.assertNotIn("γ", text.split("(")[0])  # a term only after the plain words
        labels = bpy.context.scene.hyvox.bl_rna.properties
        self.assertEqual((labels["color"].name, labels["tess_gamma"].name), ("Color", "Tessellation Density"))

    def test_frame_range_defaults_to_the_scenes(self):
        scene = bpy.context.scene
        scene.frame_start, scene.frame_end = 3, 5
        settings = scene.hyvox
        for name in ("frame_start", "frame_end", "use_frame_range"):
            settings.property_unset(name)
        settings.use_frame_range = True  # as the panel's check box does
        self.assertEqual((settings.frame_start, settings.frame_end), (3, 5))
        settings.property_unset("frame_start")
        settings.property_unset("frame_end")
        cube = helpers.cube()
        helpers.select_only(cube)
        self.voxelize(resolution=4, use_frame_range=True)  # a script that sets no frames
        names = sorted(os.listdir(self.out))
        self.assertEqual([n[-8:-4] for n in names], ["0003", "0004", "0005"])
        settings.property_unset("use_frame_range")
        scene.frame_start, scene.frame_end = 1, 250

    def test_result_selected_and_visible_source_hidden_on_request(self):
        cube = helpers.cube()
        helpers.select_only(cube)
        self.voxelize(resolution=8, hide_source=True)
        (volume,) = self.volumes()
        layer = bpy.context.view_layer
        self.assertIs(layer.objects.active, volume)
        self.assertTrue(volume.select_get() and volume.visible_get())
        self.assertFalse(cube.select_get())
        self.assertFalse(cube.visible_get())
        # Voxelize again with the result selected (as the run left it): its source runs again.
        cube.hide_set(False)
        self.assertEqual(self.voxelize(resolution=16), {"FINISHED"})
        (again,) = self.volumes()
        self.assertAlmostEqual(again["hyvox_voxel_size"], 0.125)

    def test_status_says_what_was_made(self):
        from hyvox_blender.core import summary
        from hyvox_blender.core.pipeline import Group, GroupResult, Timings

        result = GroupResult(Group("Cube", ["Cube"]), voxel_counts=[1234])
        self.assertEqual(
            summary.short_report({"Cube": result}, Timings(voxelize_ms=1500.0)),
            "Made Cube volume of 1,234 voxels in 1.50 s",
        )
