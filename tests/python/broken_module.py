# SPDX-License-Identifier: GPL-3.0-or-later
"""A hyvox package whose compiled module cannot load, for the tests of the add-on's
explanation (tests/python/test_module_diagnosis.py, tests/blender/test_module_diagnosis.py):
a real shared object built here with the C compiler, linked against a library that is
then deleted."""

import pathlib
import shutil
import subprocess
import sysconfig

GONE = "libhyvox_gone_for_test.so.1"
SUFFIX = sysconfig.get_config_var("EXT_SUFFIX")  # e.g. .cpython-311-x86_64-linux-gnu.so


def build_broken_package(root: pathlib.Path) -> pathlib.Path:
    """root/hyvox/ with __init__.py importing _core<SUFFIX>, which needs GONE (deleted)."""
    cc = shutil.which("cc") or shutil.which("gcc")
    assert cc, "a C compiler is needed to build the broken module"
    work = root / "work"
    work.mkdir()
    (work / "gone.c").write_text("int hyvox_gone(void) { return 1; }\n")
    (work / "core.c").write_text("int hyvox_gone(void);\nint PyInit__core(void) { return hyvox_gone(); }\n")
    subprocess.run(
        [cc, "-shared", "-fPIC", "-o", str(work / GONE), f"-Wl,-soname,{GONE}", str(work / "gone.c")], check=True
    )
    package = root / "hyvox"
    package.mkdir()
    subprocess.run(
        [
            cc,
            "-shared",
            "-fPIC",
            "-o",
            str(package / ("_core" + SUFFIX)),
            str(work / "core.c"),
            f"-L{work}",
            f"-l:{GONE}",
        ],
        check=True,
    )
    (work / GONE).unlink()
    (package / "__init__.py").write_text("from . import _core\nvoxelize = None\n")
    return package
