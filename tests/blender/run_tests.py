# SPDX-License-Identifier: GPL-3.0-or-later
"""Headless runner for the add-on tests:

    blender -b --factory-startup --python tests/blender/run_tests.py -- BUILD_DIR [test_x ...]

Enables hyvox_blender from BUILD_DIR/addon (as an artist's install would), runs the
unittest cases of the named test files (all test_*.py by default) and exits non-zero on
any failure, so CTest and CI see it."""

import os
import sys
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))


def main(argv):
    if len(argv) < 1:
        print("usage: blender -b --factory-startup --python run_tests.py -- BUILD_DIR [test_name ...]")
        return 2
    build_dir = os.path.abspath(argv[0])
    names = [os.path.splitext(os.path.basename(n))[0] for n in argv[1:]]
    os.environ["HYVOX_BUILD_DIR"] = build_dir
    sys.path.insert(0, HERE)
    import helpers

    helpers.enable_addon(build_dir)

    if not names:
        names = sorted(f[:-3] for f in os.listdir(HERE) if f.startswith("test_") and f.endswith(".py"))
    return helpers.run_suite(names)


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    try:
        code = main(argv)
    except Exception:
        traceback.print_exc()
        code = 1
    sys.stdout.flush()
    # os._exit: Blender would otherwise carry on (and return 0) after a --python script.
    os._exit(code)
