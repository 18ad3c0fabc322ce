# SPDX-License-Identifier: GPL-3.0-or-later
"""When the EEVEE bounds modifier (blender/volume/eevee_bounds.py) cannot be added, the
voxelization still finishes, the volume is made, nothing half-made is left behind, and the
operator warns in plain words, naming the object.

The add-on adds the modifier only in Blender 4.2-4.5; here its rule is forced on, so these
tests run the same way in every Blender (in 3.4 the nodes are really missing). The
failures are forced as they happen in a file: the nodes missing, a node group of that
name that is not the add-on's, and a failure while the group is being built."""

import contextlib
import io

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase

SIZE = 0.25  # the 2x2x2 cube: an 8^3 shell, 8^3 - 6^3 = 296 voxels


class EeveeBoundsFallbackTest(AddonTestCase):
    def setUp(self):
        super().setUp()
        self.bounds = helpers.addon("blender.volume.eevee_bounds")
        self.alignment = helpers.addon("core.alignment")
        self.rule = self.alignment.eevee_clips_last_voxel_layer
        self.patch(self.alignment, "eevee_clips_last_voxel_layer", lambda version: True)
        for group in list(bpy.data.node_groups):
            bpy.data.node_groups.remove(group)

    def patch(self, module, name, value):
        """Set module.name for this test only."""
        original = getattr(module, name)
        setattr(module, name, value)
        self.addCleanup(setattr, module, name, original)

    def voxelize_cube(self):
        """Voxelize the cube; the operator's report lines (Blender prints an operator's
        reports through sys.stdout when Python calls it) and the new Volume object."""
        cube = helpers.cube()
        helpers.select_only(cube)
        printed = io.StringIO()
        with contextlib.redirect_stdout(printed):
            result = self.voxelize(voxel_size=SIZE)
        self.assertEqual(result, {"FINISHED"})
        (obj,) = self.volumes()
        self.assertEqual(obj.name, "Cube_voxels")
        coords, _, _, _ = helpers.read_vdb(bpy.path.abspath(obj.data.filepath))
        self.assertEqual(len(np.unique(coords, axis=0)), 8**3 - 6**3)
        warnings = [line for line in printed.getvalue().splitlines() if line.startswith("Warning:")]
        print("reported:", warnings)
        return obj, warnings

    def assert_warned_without_modifier(self, obj, warnings, reason):
        self.assertEqual(len(warnings), 1, warnings)
        self.assertIn("Cube_voxels: EEVEE may not draw the last voxel layer", warnings[0])
        self.assertIn(reason, warnings[0])
        self.assertEqual([m.type for m in obj.modifiers], [])

    def test_missing_nodes(self):
        self.patch(self.bounds, "NODES_NEEDED", self.bounds.NODES_NEEDED + ("GeometryNodeNotInThisBlender",))
        obj, warnings = self.voxelize_cube()
        self.assert_warned_without_modifier(obj, warnings, "GeometryNodeNotInThisBlender")
        self.assertEqual(list(bpy.data.node_groups), [])

    def test_a_node_group_of_that_name_that_is_not_ours(self):
        """The file's own group is used as found, fails, and is kept (it is the artist's)."""
        self.patch(self.bounds, "NODES_NEEDED", ())  # in 3.4 too: reach the group
        theirs = bpy.data.node_groups.new(self.bounds.GROUP_NAME, "GeometryNodeTree")
        obj, warnings = self.voxelize_cube()
        self.assert_warned_without_modifier(obj, warnings, "Error")
        self.assertEqual(list(bpy.data.node_groups), [theirs])

    def test_failure_while_building_the_group(self):
        """A half-built group is removed, not left in the file."""
        self.patch(self.bounds, "NODES_NEEDED", ())
        self.patch(self.bounds, "MARGIN_VOXELS", "two")  # not a number: the build stops midway
        obj, warnings = self.voxelize_cube()
        self.assert_warned_without_modifier(obj, warnings, "Error")
        self.assertEqual(list(bpy.data.node_groups), [])

    def test_this_blender(self):
        """Unforced: where the rule adds the modifier (4.2-4.5) it is added without a
        warning; elsewhere there is neither. (Forced on, 5.3 refuses the modifier's input
        as an ID property: the warning, not a failure.)"""
        self.alignment.eevee_clips_last_voxel_layer = self.rule
        obj, warnings = self.voxelize_cube()
        self.assertEqual(warnings, [])
        expected = [self.bounds.MODIFIER_NAME] if self.rule(bpy.app.version) else []
        self.assertEqual([m.name for m in obj.modifiers], expected)
