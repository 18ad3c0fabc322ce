# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's side of the render-farm jobs (`hyvox job-template` prints them): what a farm
task runs inside Blender. The jobs start it without knowing where the add-on is installed:

    blender -b SCENE.blend --python-exit-code 1 --python-expr "<find the enabled hyvox add-on,
        import its farm package, call main()>" -- COMMAND ARGS...

COMMAND is
    run        voxelize frames of the job (a task's chunk), one line per frame (task.py)
    assemble   check every frame's file and save a .blend with the volume sequence (task.py)
    serve      keep this Blender for the tasks of a worker session (session.py)
Exits non-zero with the reason on failure; SIGTERM cancels and leaves no partial file."""

import os
import sys


def main(argv):
    from . import session, task

    if argv[:1] == ["serve"]:
        session.serve(argv[1:])
        return
    code = task.run_command(argv)
    if code:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)  # Blender would otherwise go on and exit 0
