# SPDX-License-Identifier: GPL-3.0-or-later
"""Scripts written against earlier versions keep working (docs/compatibility.md): the
operator's fill_interior= keyword, which Mode replaced, runs as the mode it meant (on:
solid; off: the surface mode Mode then defaulted to) with the same voxels as that mode=,
and warns, naming mode=, in the run's report and as a Python warning (FutureWarning)."""

import warnings

import bpy
import numpy as np

import helpers
from helpers import AddonTestCase


def sphere():
    bpy.ops.mesh.primitive_uv_sphere_add(radius=1.0, segments=24, ring_count=12, location=(0.1, -0.2, 0.3))
    bpy.context.active_object.name = "Sphere"


class OldKeywordsTest(AddonTestCase):
    def run_script(self, **kw):
        """Runs the operator as an earlier version's script would; (voxel centres of the new
        volume, the Python warnings). The operator's WARNING report has the same text."""
        before = set(self.volumes())
        helpers.select_only(bpy.data.objects["Sphere"])
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            result = bpy.ops.object.hyvox_voxelize(output_dir=self.out, method="cpu", resolution=24, **kw)
        self.assertEqual(result, {"FINISHED"})
        (volume,) = set(self.volumes()) - before
        centres = helpers.sorted_rows(helpers.vdb_world_centres(bpy.path.abspath(volume.data.filepath)))
        return centres, [str(w.message) for w in caught]

    def check_same_as(self, old_keywords, mode):
        sphere()
        old, old_warnings = self.run_script(**old_keywords)
        new, new_warnings = self.run_script(mode=mode)
        self.assertGreater(len(new), 0)
        np.testing.assert_array_equal(old, new)  # the same voxels, exactly
        self.assertFalse([w for w in new_warnings if "fill_interior" in w])
        deprecation = [w for w in old_warnings if "fill_interior" in w]
        self.assertEqual(len(deprecation), 1, old_warnings)
        self.assertIn("mode=", deprecation[0])
        self.assertIn(f"mode='{mode}'", deprecation[0])
        return old

    def test_fill_interior_on_is_solid(self):
        solid = self.check_same_as({"fill_interior": True}, "solid")
        # Really filled: more voxels than the shell of the same sphere.
        shell, _ = self.run_script(mode="conservative")
        self.assertGreater(len(solid), 2 * len(shell))

    def test_fill_interior_off_is_the_old_surface_default(self):
        self.assertEqual(bpy.context.scene.hyvox.mode, "solid")  # this version's default
        self.check_same_as({"fill_interior": False}, "conservative")

    def test_fill_interior_off_keeps_a_given_surface_mode(self):
        self.check_same_as({"fill_interior": False, "mode": "thin"}, "thin")

    def test_fill_interior_on_wins_over_mode_as_before(self):
        self.check_same_as({"fill_interior": True, "mode": "thin"}, "solid")


if __name__ == "__main__":
    helpers.run_suite([OldKeywordsTest])
