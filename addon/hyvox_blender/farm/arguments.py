# SPDX-License-Identifier: GPL-3.0-or-later
"""The parser of the farm commands (`run`, `assemble`), built from the farm task's table that
the native module declares (hyvox._core.FARM_TASK_ARGUMENTS, native/include/hyvox/farm_task.h):
the jobs (`hyvox job-template`) write their command lines from the same table, so the flags a
job writes are the flags this parser takes. bpy-free, so it is tested outside Blender."""

import argparse

_TYPES = {"str": str, "int": int, "float": float}


def parser(command, table):
    """The argparse parser of `command` ("run" or "assemble") from `table`."""
    out = argparse.ArgumentParser(prog=f"hyvox farm {command}", add_help=False)
    for arg in table:
        if command not in arg.commands:
            continue
        flags = [arg.flag, *arg.aliases]
        if arg.type == "bool":
            out.add_argument(*flags, action="store_true", help=arg.help)
        else:
            out.add_argument(*flags, required=arg.required, type=_TYPES[arg.type], default=arg.default, help=arg.help)
    return out


def parse(command, args, table):
    """(the command's own arguments, the others): `run` passes the others on to the headless
    script (cli_blender.py), `assemble` refuses them (ValueError). argparse's errors exit
    (SystemExit 2) with its message on stderr."""
    known, rest = parser(command, table).parse_known_args(args)
    if command == "assemble" and rest:
        raise ValueError(f"assemble does not take {' '.join(rest)}")
    return known, rest
