# SPDX-License-Identifier: GPL-3.0-or-later
"""The temporary folders that hold the results of unsaved files (naming.unsaved_output_dir):
one per Blender session, made by mkdtemp, with a small OWNER_FILE naming the process that
made it, and their removal once no session needs them.

- After a save has moved the results next to the .blend, the session's folder is empty and
  goes (remove_if_empty).
- On quit the session's folder goes if empty. If it still holds results of an unsaved file,
  it stays: Blender's File > Recover > Last Session (quit.blend) and the autosaves point at
  them.
- A folder of a session that has ended (its process is gone, or its number now belongs to
  a process started later) goes once nothing in it has changed for STALE_AFTER_S, leaving
  time to recover that session. A folder whose owner runs, or cannot be told, stays; one
  without OWNER_FILE (made by an earlier version) goes only when empty; one holding a file
  hyvox did not write stays. So no running session ever loses a file."""

import json
import os
import shutil
import tempfile
import time
from typing import Callable, List, Optional

PREFIX = "hyvox_cache_unsaved_"
OWNER_FILE = ".hyvox_owner"
STALE_AFTER_S = 3 * 24 * 3600
STAGING_SUFFIX = ".partial"  # naming.staging_path: a run's files before they are committed


def _read(path: str) -> Optional[str]:
    try:
        with open(path) as f:
            return f.read()
    except OSError:
        return None


def process_identity(pid: int) -> Optional[dict]:
    """What tells this process apart from a later one with the same number: the boot and
    the start time (Linux /proc); None where this system does not say (then the process
    number alone is known)."""
    stat = _read(f"/proc/{pid}/stat")
    boot = _read("/proc/sys/kernel/random/boot_id")
    if stat is None or boot is None:
        return None
    # The fields after the command name (which may hold spaces) in parentheses; field 22
    # of the line is the start time in clock ticks after boot.
    fields = stat[stat.rindex(")") + 2 :].split()
    return {"boot": boot.strip(), "start": fields[19]}


def make(parent: Optional[str] = None) -> str:
    """A new session folder (mkdtemp: never another session's) with its OWNER_FILE."""
    folder = tempfile.mkdtemp(prefix=PREFIX, dir=parent)
    owner = {"pid": os.getpid(), "identity": process_identity(os.getpid())}
    with open(os.path.join(folder, OWNER_FILE), "w") as f:
        json.dump(owner, f)
    return folder


def owner_running(folder: str) -> Optional[bool]:
    """True: the process that made the folder runs; False: it has ended; None: no
    OWNER_FILE, or this system cannot tell."""
    text = _read(os.path.join(folder, OWNER_FILE))
    try:
        owner = json.loads(text) if text is not None else None
        pid = int(owner["pid"])
    except (ValueError, TypeError, KeyError):
        return None
    recorded = owner.get("identity")
    if recorded is not None:
        current = process_identity(pid)
        if current is None:
            # No /proc entry: gone, if this system has /proc at all.
            return False if os.path.isdir("/proc/self") else None
        return current == recorded
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # another user's process: it exists
        return True
    return True


def _contents(folder: str) -> List[str]:
    try:
        return os.listdir(folder)
    except OSError:
        return []


def _last_change(folder: str) -> float:
    times = []
    for path in [folder] + [os.path.join(folder, n) for n in _contents(folder)]:
        try:
            times.append(os.stat(path).st_mtime)
        except OSError:
            pass
    return max(times) if times else 0.0


def removable(folder: str, is_voxel_file: Callable[[str], bool], now: Optional[float] = None) -> bool:
    """Whether a folder of another session can go (see the module's docstring)."""
    names = [n for n in _contents(folder) if n != OWNER_FILE]
    if any(not (is_voxel_file(n) or n.endswith(STAGING_SUFFIX)) for n in names):
        return False  # not only what hyvox writes
    running = owner_running(folder)
    if running is None:
        return not names and os.path.exists(folder) and not os.path.exists(os.path.join(folder, OWNER_FILE))
    if running:
        return False
    return not names or (time.time() if now is None else now) - _last_change(folder) > STALE_AFTER_S


def remove(folder: str) -> bool:
    try:
        shutil.rmtree(folder)
    except OSError:
        return False
    return True


def remove_if_empty(folder: Optional[str]) -> bool:
    """Remove a session folder that holds nothing but its OWNER_FILE."""
    if not folder or not os.path.isdir(folder):
        return False
    if [n for n in _contents(folder) if n != OWNER_FILE]:
        return False
    return remove(folder)


def sweep(
    is_voxel_file: Callable[[str], bool],
    own: Optional[str] = None,
    parent: Optional[str] = None,
    now: Optional[float] = None,
) -> List[str]:
    """Remove the removable session folders in the temporary folder (not `own`); returns
    the folders removed."""
    parent = parent or tempfile.gettempdir()
    removed = []
    for name in _contents(parent):
        folder = os.path.join(parent, name)
        if not name.startswith(PREFIX) or not os.path.isdir(folder) or os.path.islink(folder):
            continue
        if own and os.path.realpath(folder) == os.path.realpath(own):
            continue
        if removable(folder, is_voxel_file, now) and remove(folder):
            removed.append(folder)
    return removed
