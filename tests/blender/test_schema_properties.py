# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's settings are the options schema's: the Scene's hard limits, the operator's
soft limits, defaults and enum choices equal hyvox.OPTIONS (read back from bl_rna), an
operator value out of the limits is refused with the schema's own message (the one the CLI
and hyvox.voxelize give), and the redo panel shows the values the run used."""

import math

import bpy

import helpers
from helpers import AddonTestCase

FLOAT32_MAX = 3.4028234e38
INT32_MAX = 2**31 - 1


def expected_limits(spec):
    """Blender's limits are inclusive float32/int32: an exclusive minimum moves up by 1e-6."""
    low = spec.min + (1e-6 if spec.min_exclusive else 0.0)
    bound = INT32_MAX if spec.type == "int" else FLOAT32_MAX
    return max(low, -bound), min(spec.max, bound)


def close(a, b):
    return math.isclose(a, b, rel_tol=1e-6, abs_tol=1e-9)


class SchemaPropertiesTest(AddonTestCase):
    def setUp(self):
        super().setUp()
        self.properties = helpers.addon("blender.ui.properties")
        self.hyvox = helpers.hyvox_module()
        self.scene_rna = bpy.context.scene.hyvox.bl_rna.properties
        self.op_rna = bpy.ops.object.hyvox_voxelize.get_rna_type().properties
        self.prefs_rna = helpers.addon_preferences().bl_rna.properties

    def specs(self, names, numeric=True):
        specs = [self.hyvox.option(name) for name in names]
        return [s for s in specs if s.type in ("int", "float")] if numeric else specs

    def test_scene_and_preferences_hard_limits_are_the_schema_limits(self):
        for rna, names in (
            (self.scene_rna, self.properties.SCENE_OPTIONS),
            (self.prefs_rna, self.properties.PREFERENCE_OPTIONS),
        ):
            for spec in self.specs(names):
                with self.subTest(spec.name):
                    low, high = expected_limits(spec)
                    prop = rna[spec.name]
                    self.assertTrue(
                        close(prop.hard_min, low) and close(prop.hard_max, high),
                        (prop.hard_min, prop.hard_max, low, high),
                    )
                    self.assertIn(spec.help[1:], prop.description)
                    self.assertEqual(prop.name, spec.label)
                    if spec.default is not None:
                        self.assertTrue(close(prop.default, spec.default), (prop.default, spec.default))

    def test_operator_soft_limits_are_the_schema_limits(self):
        for spec in self.specs(self.properties.SCENE_OPTIONS):
            with self.subTest(spec.name):
                op_prop, scene_prop = self.op_rna[spec.name], self.scene_rna[spec.name]
                # Same definition as the scene's, with the limits moved to the soft ones.
                self.assertEqual(
                    (op_prop.name, op_prop.description, op_prop.type),
                    (scene_prop.name, scene_prop.description, scene_prop.type),
                )
                low, high = expected_limits(spec)
                self.assertTrue(op_prop.soft_min >= low and op_prop.soft_max <= high)
                self.assertTrue(op_prop.hard_min <= low and op_prop.hard_max >= high)

    def test_enum_choices_are_the_schemas(self):
        for rna in (self.scene_rna, self.op_rna):
            self.assertEqual([i.identifier for i in rna["mode"].enum_items], list(self.hyvox.option("mode").choices))
            self.assertEqual(
                [i.identifier for i in rna["method"].enum_items], ["auto"] + list(self.hyvox.option("method").choices)
            )

    def bad_values(self, spec):
        below = spec.min if spec.min_exclusive else spec.min - 1
        values = [below] if math.isfinite(spec.min) else []
        if math.isfinite(spec.max):
            values.append(spec.max + 1)
        return [int(v) if spec.type == "int" else float(v) for v in values]

    def test_operator_refuses_out_of_range_with_the_schema_message(self):
        cube = helpers.cube()
        helpers.select_only(cube)
        for spec in self.specs(self.properties.SCENE_OPTIONS):
            for value in self.bad_values(spec):
                with self.subTest(f"{spec.name}={value}"):
                    with self.assertRaises(ValueError) as schema:
                        self.hyvox.check_option(spec.name, value)
                    before = self.scene_state()
                    with self.assertRaises(RuntimeError) as caught:
                        self.voxelize(**{spec.name: value})
                    self.assertIn(str(schema.exception), str(caught.exception))
                    self.assertEqual(self.scene_state(), before)

    def test_operator_refuses_an_unknown_choice(self):
        cube = helpers.cube()
        helpers.select_only(cube)
        for name in ("mode", "method"):
            with self.assertRaises(TypeError) as caught:
                self.voxelize(**{name: "bogus"})
            self.assertIn("bogus", str(caught.exception))
            for choice in self.hyvox.option(name).choices:
                self.assertIn(choice, str(caught.exception))

    def test_the_run_records_what_it_used(self):
        # What the operator writes back into its properties (the redo panel: checked in a
        # window by interactive_modal.py) is also in the run's record.
        operators = helpers.addon("blender.operators")
        cube = helpers.cube()
        helpers.select_only(cube)
        scene = bpy.context.scene.hyvox
        scene.resolution = 12
        scene.padding = 2
        self.assertEqual(self.voxelize(mode="thin"), {"FINISHED"})
        used = operators.last_run_record["settings"]
        # The scene's values (not the operator's own defaults) and the script's override.
        self.assertEqual((used["resolution"], used["padding"], used["mode"], used["method"]), (12, 2, "thin", "cpu"))
        volume = self.volumes()[0]
        voxel_size = helpers.read_vdb(bpy.path.abspath(volume.data.filepath))[1]
        self.assertAlmostEqual(float(voxel_size[0]), 2.0 / 12, places=6)  # the 2-unit cube at resolution 12
        scene.property_unset("padding")
