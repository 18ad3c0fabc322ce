# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on tests in official Blender 4.2+ run as the `bpy` module (PyPI), with the
add-on installed as an extension the way an artist installs it:

    B/venv/bpy45/bin/python tests/blender/run_bpy_tests.py BUILD_DIR [test_x ...]

A fresh, empty Blender user folder (BLENDER_USER_RESOURCES) per run; the extension zip
B/hyvox_blender-*-linux_x64.zip (or $HYVOX_EXTENSION_ZIP: a release's) is installed there with Install from Disk's operator,
which also installs its bundled wheel into that folder's site-packages and enables it.
Then the named unittest files run as under run_tests.py (no skips allowed)."""

import glob
import os
import sys
import tempfile
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))


def install_extension(build_dir, user_dir):
    import bpy

    given = os.environ.get("HYVOX_EXTENSION_ZIP")
    (zip_path,) = [given] if given else glob.glob(os.path.join(build_dir, "hyvox_blender-*-linux_x64.zip"))
    result = bpy.ops.extensions.package_install_files(filepath=zip_path, repo="user_default", enable_on_install=True)
    if result != {"FINISHED"}:
        raise RuntimeError(f"installing {zip_path} returned {result}")
    import helpers

    helpers.ADDON_PACKAGE = "bl_ext.user_default.hyvox_blender"
    if helpers.ADDON_PACKAGE not in bpy.context.preferences.addons:
        raise RuntimeError(f"{zip_path} installed but {helpers.ADDON_PACKAGE} is not enabled")
    helpers.ADDON_DIR = os.path.join(user_dir, "extensions", "user_default", "hyvox_blender")
    # Where Blender installs an extension's wheels (one site-packages per user folder).
    helpers.MODULE_DIR = os.path.join(
        user_dir, "extensions", ".local", "lib", "python%d.%d" % sys.version_info[:2], "site-packages", "hyvox"
    )


def main(argv):
    if len(argv) < 2:
        print("usage: python run_bpy_tests.py BUILD_DIR test_name [test_name ...]")
        return 2
    build_dir = os.path.abspath(argv[0])
    names = [n[:-3] if n.endswith(".py") else n for n in argv[1:]]  # test_x or test_x.Case.test_y
    with tempfile.TemporaryDirectory(prefix="hyvox-blender-user-") as user_dir:
        # Read when bpy is first imported: nothing of the machine's own Blender set-up.
        os.environ["BLENDER_USER_RESOURCES"] = user_dir
        os.environ["HYVOX_BUILD_DIR"] = build_dir
        sys.path.insert(0, HERE)
        import bpy
        import helpers  # after bpy's first import (it imports bpy)

        print("Blender", bpy.app.version_string, "Python", sys.version.split()[0])
        install_extension(build_dir, user_dir)
        return helpers.run_suite(names)


if __name__ == "__main__":
    try:
        code = main(sys.argv[1:])
    except Exception:
        traceback.print_exc()
        code = 1
    sys.stdout.flush()
    os._exit(code)  # bpy's exit handlers would otherwise run after a failed test's state
