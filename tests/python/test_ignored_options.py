# SPDX-License-Identifier: GPL-3.0-or-later
# An option the chosen method does not use is ignored with a word from every front door:
# the CLI's warning (test_option_schema.py), hyvox.IgnoredOptionWarning from the module, an
# INFO report from the add-on, all from the schema's one rule (OptionSpec.applies_to).
import os
import sys
import warnings

import numpy as np
import pytest

import hyvox
from test_option_schema import METHOD_GROUPS, TETRA_T, TETRA_V, cli_text, good_value

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "addon"))

from hyvox_blender.core import backend  # noqa: E402
from hyvox_blender.core.pipeline import Group, GroupMesh, Pipeline  # noqa: E402
from hyvox_blender.core.settings import VoxelizeSettings  # noqa: E402

TETRA = (TETRA_V, TETRA_T)


def expected_to_apply(spec, method):
    """The oracle, written out from the schema's groups: grid and run options apply to every
    method, the others to the methods of their group."""
    return spec.group not in METHOD_GROUPS or method in METHOD_GROUPS[spec.group]


@pytest.mark.parametrize("spec", hyvox.OPTIONS, ids=lambda s: s.name)
def test_applies_to_follows_the_groups(spec):
    for method in hyvox.METHODS:
        assert spec.applies_to(method) == expected_to_apply(spec, method), method
    with pytest.raises(ValueError, match="unknown method 'gpu'"):
        spec.applies_to("gpu")


@pytest.mark.parametrize("spec", [s for s in hyvox.OPTIONS if s.group in METHOD_GROUPS], ids=lambda s: s.name)
def test_voxelize_warns_about_an_option_the_method_ignores_and_really_ignores_it(spec):
    value = good_value(spec)
    with pytest.warns(hyvox.IgnoredOptionWarning) as caught:
        grid = hyvox.voxelize(*TETRA, resolution=8, method="cpu", **{spec.name: value})
    assert [str(w.message) for w in caught] == [f"{spec.name} does not apply to the cpu method: ignored"]
    assert caught[0].filename == __file__  # points at the caller's line
    assert np.array_equal(grid.coords(), hyvox.voxelize(*TETRA, resolution=8, method="cpu").coords())


def test_the_warning_says_what_the_cli_says(cli_voxelize, tmp_path, tetra_obj):
    spec = hyvox.option("tess_gamma")
    done = cli_voxelize(
        tetra_obj, tmp_path / "o.vdb", "-q", "--method=reference", f"{spec.cli_flag}={cli_text(good_value(spec))}"
    )
    with pytest.warns(hyvox.IgnoredOptionWarning) as caught:
        hyvox.voxelize(*TETRA, resolution=8, method="reference", tess_gamma=good_value(spec))
    assert done.stderr.strip() == "hyvox: warning: " + str(caught[0].message).replace(spec.name, spec.cli_flag)


def test_options_that_apply_unset_ones_and_the_environment_do_not_warn(monkeypatch):
    monkeypatch.setenv("HYVOX_GL_DEVICE", "software")  # read for every call; cpu does not use it
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        hyvox.voxelize(*TETRA, resolution=8, method="cpu", threads=2, padding=1, tess_gamma=None, hybrid_cutoff=None)
        hyvox.voxelize(*TETRA, resolution=8, method="hybrid", hybrid_cutoff=4.0, gl_device="software")


def test_ignored_options_keeps_the_order_and_names_unknown_options():
    assert hyvox.ignored_options("cpu", ["tess_gamma", "resolution", "gl_device", "hybrid_cutoff"]) == [
        "tess_gamma",
        "gl_device",
        "hybrid_cutoff",
    ]
    assert hyvox.ignored_options("tessellation", ["tess_gamma", "gl_device", "hybrid_cutoff"]) == ["hybrid_cutoff"]
    with pytest.raises(KeyError):
        hyvox.ignored_options("cpu", ["no_such_option"])


def test_the_addon_reports_changed_settings_another_method_uses_and_passes_none_of_them(tmp_path):
    def export(frame):
        return [GroupMesh(Group("T", ["T"]), *TETRA)]

    # tess_gamma changed, hybrid_cutoff and gl_device at their defaults: only the changed one
    # is news (the add-on passes every setting on every run).
    settings = VoxelizeSettings(
        method="cpu", resolution=8, tess_gamma=8.0, hybrid_cutoff=hyvox.option("hybrid_cutoff").default, gl_device=""
    )
    pipeline = Pipeline(settings, str(tmp_path), export, module=hyvox)
    assert pipeline.ignored_options == ["tess_gamma"]
    assert (
        backend.ignored_message(pipeline.ignored_options, "cpu")
        == "tess_gamma does not apply to the cpu method: ignored"
    )
    assert backend.ignored_message(["a", "b"], "cpu") == "a, b do not apply to the cpu method: ignored"
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the module is not handed the options it would warn about
        (result,) = pipeline.run().values()
    assert result.voxel_counts == [hyvox.voxelize(*TETRA, resolution=8, method="cpu").voxel_count]
    # For the method that uses them, nothing is ignored.
    assert Pipeline(
        VoxelizeSettings(method="tessellation", resolution=8, tess_gamma=8.0, hybrid_cutoff=2.0),
        str(tmp_path),
        export,
        module=hyvox,
    ).ignored_options == ["hybrid_cutoff"]
