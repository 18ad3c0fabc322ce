# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's side of the render-farm jobs (`hyvox job-template` prints them): what a farm
task runs inside Blender. The jobs start it without knowing where the add-on is installed or
what is inside it:

    blender -b SCENE.blend --python-exit-code 1 --python-expr "<enable the installed add-on
        named hyvox_blender, call its farm_main()>" -- COMMAND ARGS...

COMMAND is
    run        voxelize frames of the job (a task's chunk), one line per frame (task.py)
    assemble   check every frame's file and save a .blend with the volume sequence (task.py)
    serve      keep this Blender for the tasks of a worker session (session.py)
The arguments of run and assemble are the farm task's table (arguments.py), the one the jobs
write their command lines from. Exits non-zero with the reason on failure; SIGTERM cancels
and leaves no partial file."""

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
