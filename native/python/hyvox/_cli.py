# SPDX-License-Identifier: GPL-3.0-or-later
"""The `hyvox` console command of the wheel: runs the CLI binary installed inside the
package (hyvox/bin/hyvox), so pip's script and the native tool are one program."""

import os
import sys


def binary_path() -> str:
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", "hyvox")


def main() -> None:
    path = binary_path()
    if not os.access(path, os.X_OK):
        sys.exit(f"hyvox: the CLI binary is missing from the installed package ({path})")
    os.execv(path, [path] + sys.argv[1:])


if __name__ == "__main__":
    main()
