# SPDX-License-Identifier: GPL-3.0-or-later
"""The temporary folders of unsaved sessions (core/session_folder.py): a folder goes only when
no running session can need it, with real processes as the owners (one that has ended, one
that still runs) and the folder's own times."""

import json
import os
import subprocess
import sys
import time

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "addon"))

from hyvox_blender.core import naming, session_folder  # noqa: E402

ADDON = os.path.join(os.path.dirname(__file__), "..", "..", "addon")
MAKE = (
    "import sys; from hyvox_blender.core import session_folder; "
    "print(session_folder.make(sys.argv[1]), flush=True); sys.stdin.read()"
)


def other_session(parent):
    """A process that makes its own session folder in `parent` and runs until its stdin closes."""
    child = subprocess.Popen(
        [sys.executable, "-c", MAKE, str(parent)],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
        env=dict(os.environ, PYTHONPATH=ADDON),
    )
    return child, child.stdout.readline().strip()


def end(child):
    child.stdin.close()
    child.wait(timeout=30)


def age(folder, seconds):
    """Set the folder's and its files' times `seconds` into the past."""
    then = time.time() - seconds
    for path in [folder] + [os.path.join(folder, n) for n in os.listdir(folder)]:
        os.utime(path, (then, then))


def voxel_file(folder, name="Cube_voxels_r0a1b2cx.vdb"):
    with open(os.path.join(folder, name), "wb") as f:
        f.write(b"x")


def test_the_own_folder_names_this_process(tmp_path):
    folder = session_folder.make(str(tmp_path))
    assert os.path.basename(folder).startswith(session_folder.PREFIX)
    with open(os.path.join(folder, session_folder.OWNER_FILE)) as f:
        assert json.load(f)["pid"] == os.getpid()
    assert session_folder.owner_running(folder) is True
    assert not session_folder.removable(folder, naming.is_voxel_file)


def test_a_running_sessions_folder_stays_however_old(tmp_path):
    child, folder = other_session(tmp_path)
    try:
        voxel_file(folder)
        age(folder, 10 * session_folder.STALE_AFTER_S)
        assert session_folder.owner_running(folder) is True
        assert session_folder.sweep(naming.is_voxel_file, parent=str(tmp_path)) == []
        assert os.path.isfile(os.path.join(folder, "Cube_voxels_r0a1b2cx.vdb"))
    finally:
        end(child)


def test_an_ended_sessions_folder_goes_when_stale(tmp_path):
    child, full = other_session(tmp_path)
    end(child)
    voxel_file(full)
    child, empty = other_session(tmp_path)
    end(child)
    assert session_folder.owner_running(full) is False
    # Results of an unsaved file stay for File > Recover until stale; an empty folder goes now.
    assert session_folder.sweep(naming.is_voxel_file, parent=str(tmp_path)) == [empty]
    assert os.path.isdir(full)
    age(full, session_folder.STALE_AFTER_S + 60)
    assert session_folder.sweep(naming.is_voxel_file, parent=str(tmp_path)) == [full]
    assert os.listdir(tmp_path) == []


def test_a_reused_process_number_is_not_the_owner(tmp_path):
    folder = session_folder.make(str(tmp_path))
    owner_file = os.path.join(folder, session_folder.OWNER_FILE)
    with open(owner_file) as f:
        owner = json.load(f)
    if owner["identity"] is None:
        pytest.fail("this system does not tell processes apart by start time (/proc)")
    owner["identity"]["start"] = str(int(owner["identity"]["start"]) - 1)  # started earlier: another process
    with open(owner_file, "w") as f:
        json.dump(owner, f)
    assert session_folder.owner_running(folder) is False


def test_folders_that_are_not_only_hyvox_files_or_unknown_stay(tmp_path):
    child, foreign = other_session(tmp_path)
    end(child)
    with open(os.path.join(foreign, "notes.txt"), "w") as f:
        f.write("mine")
    age(foreign, 10 * session_folder.STALE_AFTER_S)
    older_empty = tmp_path / (session_folder.PREFIX + "old1")  # an earlier version's: no owner file
    older_full = tmp_path / (session_folder.PREFIX + "old2")
    older_empty.mkdir()
    older_full.mkdir()
    voxel_file(str(older_full))
    age(str(older_full), 10 * session_folder.STALE_AFTER_S)
    not_ours = tmp_path / "something_else"
    not_ours.mkdir()
    assert session_folder.sweep(naming.is_voxel_file, parent=str(tmp_path)) == [str(older_empty)]
    assert sorted(os.listdir(tmp_path)) == sorted([os.path.basename(foreign), older_full.name, not_ours.name])


def test_the_own_folder_is_never_swept_and_goes_when_empty(tmp_path):
    own = session_folder.make(str(tmp_path))
    os.remove(os.path.join(own, session_folder.OWNER_FILE))  # even looking like an earlier version's
    assert session_folder.sweep(naming.is_voxel_file, own=own, parent=str(tmp_path)) == []
    voxel_file(own)
    assert not session_folder.remove_if_empty(own)
    os.remove(os.path.join(own, "Cube_voxels_r0a1b2cx.vdb"))
    assert session_folder.remove_if_empty(own) and not os.path.exists(own)
