# SPDX-License-Identifier: GPL-3.0-or-later
"""Why the compiled hyvox module does not load, in plain words: which file, which Python
it was built for, which library is missing.

Python's own ImportError is often misleading here (a missing shared library can surface
as "cannot import name '_core' from partially initialized module ... circular import"),
so this looks at the files: the extension's name says the Python it was built for, and
asking the system loader to open it (ctypes, no Python init) gives the loader's own
message, e.g. "libopenvdb.so.10.0: cannot open shared object file"; ldd lists every
library it cannot find."""

import ctypes
import glob
import importlib.machinery
import os
import re
import shutil
import subprocess
import sys
from typing import List, Optional

_ABI_TAG = re.compile(r"\.cpython-(\d)(\d+)-([\w-]+?)\.so$")
_MISSING = re.compile(r"([\w.+-]+\.so[\w.]*): cannot open shared object file")
_UNDEFINED = re.compile(r"undefined symbol: (\S+)")


def running_python() -> str:
    return "Python %d.%d" % sys.version_info[:2]


def built_for(path: str) -> str:
    """'Python 3.11 (x86_64-linux-gnu)' from the extension's file name."""
    match = _ABI_TAG.search(os.path.basename(path))
    if not match:
        return "an unknown Python (the file name has no cpython-XY tag)"
    major, minor, platform = match.groups()
    return f"Python {major}.{minor} ({platform})"


def loader_error(path: str) -> Optional[str]:
    """The system loader's message for opening the file, None when it opens."""
    try:
        ctypes.CDLL(path, mode=os.RTLD_LOCAL)
    except OSError as exc:
        return str(exc)
    return None


def libraries_not_found(path: str) -> List[str]:
    """Every library ldd cannot resolve for the file (empty where there is no ldd)."""
    ldd = shutil.which("ldd") or ("/usr/bin/ldd" if os.path.exists("/usr/bin/ldd") else None)
    if not ldd:
        return []
    try:
        out = subprocess.run([ldd, path], capture_output=True, text=True, timeout=30).stdout
    except (OSError, subprocess.SubprocessError):
        return []
    return [line.split("=>")[0].strip() for line in out.splitlines() if "not found" in line]


def explain(package_dir: str, error: BaseException) -> str:
    """The artist-facing explanation for a failed import of the package in package_dir."""
    lines = ["hyvox could not load its compiled module."]
    modules = sorted(glob.glob(os.path.join(package_dir, "_core*.so")))
    if not modules:
        lines.append(f"No compiled module (_core*.so) is in {package_dir}: install a hyvox build that includes it.")
    suffixes = importlib.machinery.EXTENSION_SUFFIXES
    for path in modules:
        lines.append(f"File: {path}")
        lines.append(f"Built for: {built_for(path)}; this Blender runs {running_python()}.")
        # Python imports _core only from _core + one of its suffixes, exactly.
        if os.path.basename(path)[len("_core") :] not in suffixes:
            lines.append(
                f"This Python cannot load it (it loads {', '.join(suffixes)}): install the "
                f"hyvox build made for {running_python()}."
            )
            continue
        message = loader_error(path) or ""
        missing = libraries_not_found(path)
        match = _MISSING.search(message)
        if match and match.group(1) not in missing:
            missing.insert(0, match.group(1))
        if missing:
            lines.append(
                "Missing libraries: " + ", ".join(missing) + ". They are not installed "
                "here (or not where the loader looks); the Blender 4.2+ extension and the "
                "pip wheel bundle them."
            )
        elif _UNDEFINED.search(message):
            lines.append(
                f"A library it needs is a different version than it was built against "
                f"({_UNDEFINED.search(message).group(0)})."
            )
        elif message:
            lines.append(f"The system loader says: {message}")
    lines.append(f"(Python's error: {type(error).__name__}: {error})")
    return "\n".join(lines)
