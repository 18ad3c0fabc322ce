# SPDX-License-Identifier: GPL-3.0-or-later
"""When the compiled module cannot load, the add-on says which file, which Python it was
built for and which library is missing (hyvox_blender.core.module_diagnosis), instead of
Python's misleading ImportError. The broken modules (broken_module.py) are real shared
objects: one linked against a library that is then deleted, and the same one named for
another Python."""

import pathlib
import shutil
import subprocess
import sys

import pytest

ADDON = pathlib.Path(__file__).resolve().parents[2] / "addon"
sys.path.insert(0, str(ADDON))
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))

from broken_module import GONE, SUFFIX, build_broken_package  # noqa: E402
from hyvox_blender.core import module_diagnosis  # noqa: E402

THIS_PYTHON = "Python %d.%d" % sys.version_info[:2]


@pytest.fixture
def broken(tmp_path):
    return build_broken_package(tmp_path)


def import_error(package: pathlib.Path) -> ImportError:
    code = f"import sys; sys.path.insert(0, {str(package.parent)!r}); import hyvox"
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env={"PATH": "/usr/bin:/bin"})
    assert run.returncode != 0
    return ImportError(run.stderr.strip().splitlines()[-1])


def test_missing_library_named(broken):
    text = module_diagnosis.explain(str(broken), import_error(broken))
    assert f"File: {broken / ('_core' + SUFFIX)}" in text
    assert f"Built for: {THIS_PYTHON} (" in text
    assert f"this Blender runs {THIS_PYTHON}" in text
    assert f"Missing libraries: {GONE}." in text


def test_module_for_another_python(broken):
    other = "_core.cpython-399-x86_64-linux-gnu.so"
    (broken / ("_core" + SUFFIX)).rename(broken / other)
    text = module_diagnosis.explain(str(broken), ImportError("cannot import name '_core'"))
    assert f"File: {broken / other}" in text
    assert "Built for: Python 3.99 (x86_64-linux-gnu)" in text
    assert f"install the hyvox build made for {THIS_PYTHON}" in text
    assert "Missing libraries" not in text


def test_no_module_file(tmp_path):
    (tmp_path / "hyvox").mkdir()
    text = module_diagnosis.explain(str(tmp_path / "hyvox"), ImportError("x"))
    assert "No compiled module (_core*.so)" in text


def test_loading_add_on_reports_it(broken, tmp_path):
    # The add-on's loader, with the broken package bundled where the build puts it.
    addon = tmp_path / "addon"
    shutil.copytree(
        ADDON / "hyvox_blender", addon / "hyvox_blender", ignore=shutil.ignore_patterns("__pycache__", "hyvox")
    )
    shutil.copytree(broken, addon / "hyvox_blender" / "hyvox")
    code = (
        f"import sys; sys.path.insert(0, {str(addon)!r})\n"
        "from hyvox_blender.core import backend, errors\n"
        "try:\n    backend.load_module()\n"
        "except errors.ModuleMissingError as exc:\n    print(exc)\n"
    )
    run = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env={"PATH": "/usr/bin:/bin"}, check=True
    )
    assert f"Missing libraries: {GONE}." in run.stdout, run.stdout + run.stderr
    assert f"File: {addon / 'hyvox_blender' / 'hyvox' / ('_core' + SUFFIX)}" in run.stdout
