# SPDX-License-Identifier: GPL-3.0-or-later
"""A setting the chosen method does not use is reported (INFO) by the operator, and the run
still voxelizes exactly what the module gives without it."""

import sys
import warnings

import helpers
from helpers import AddonTestCase


class IgnoredOptionTest(AddonTestCase):
    def run_recording_reports(self, **kw):
        """The "does not apply" report texts the operator made (an RNA method such as
        Operator.report cannot be wrapped from Python; the text it is given can), with
        hyvox's warnings turned into errors."""
        backend = sys.modules["hyvox_blender.core.backend"]
        original = backend.ignored_message
        reports = []

        def recording(names, method):
            reports.append(original(names, method))
            return reports[-1]

        backend.ignored_message = recording
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("error")
                self.assertEqual(self.voxelize(**kw), {"FINISHED"})
        finally:
            backend.ignored_message = original
        return reports

    def test_a_changed_setting_of_another_method_is_reported(self):
        cube = helpers.cube()
        helpers.select_only(cube)
        reports = self.run_recording_reports(method="cpu", resolution=8, tess_gamma=8.0)
        self.assertEqual(reports, ["tess_gamma does not apply to the cpu method: ignored"])
        self.assertEqual(len(self.volumes()), 1)
        # The same settings the method does use: no such report.
        self.assertEqual(self.run_recording_reports(method="tessellation", resolution=8, tess_gamma=8.0), [])
