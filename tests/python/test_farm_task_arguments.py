# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's parser of the farm commands, built from the farm task's one table
(hyvox/farm_task.h, hyvox._core.FARM_TASK_ARGUMENTS; farm/arguments.py): what it accepts and
refuses, its messages, and what the flags mean. The jobs' own command lines, written from the
same table, go through it in the farm tests (tests/farm/)."""

import contextlib
import io
import os
import sys

import pytest

import hyvox

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "addon"))

from hyvox_blender.farm import arguments  # noqa: E402

TABLE = hyvox._core.FARM_TASK_ARGUMENTS
JOB = ["--job-frames", "1-250", "--output", "/out"]

# (command, arguments, accepted)
CASES = [
    ("run", ["--frames", "1-10", *JOB], True),
    ("run", ["--frames=1-10", "--job-frames=1-250", "-o", "/out", "--objects", ""], True),
    ("run", ["--frames", "1-10", *JOB, "--resolution", "64", "--voxel-size", "0"], True),
    ("run", ["--frames", "1-10", *JOB, "-r", "-3", "--voxel-size", "-.5"], True),  # negative numbers are values
    ("run", ["--frames", "1-10", *JOB, "--voxel-size", "1e-3", "--viewport", "--blend", "a b.blend"], True),
    ("run", ["--frames", "1-10", *JOB, "--mode", "solid", "--method", "cpu"], True),  # passed on
    ("run", ["--frames", "1-10", *JOB, "--frames", "11-20"], True),  # the last wins
    ("run", ["--frames", "1-10", *JOB, "-o=/elsewhere"], True),
    ("run", ["--frames", "1-10", *JOB, "--", "--whatever"], True),
    ("run", JOB, False),  # --frames is required
    ("run", ["--frames", "1-10", "--output", "/out"], False),
    ("run", ["--frames", "1-10", "--job-frames", "1-250"], False),
    ("run", ["--frames", "1-10", *JOB, "--resolution", "sixty"], False),
    ("run", ["--frames", "1-10", *JOB, "--resolution", "6.5"], False),
    ("run", ["--frames", "1-10", *JOB, "--resolution=0x40"], False),
    ("run", ["--frames", "1-10", *JOB, "--voxel-size", "tiny"], False),
    ("run", ["--frames", "1-10", *JOB, "--voxel-size"], False),  # no value
    ("run", ["--frames", "--job-frames", "1-250", "--output", "/out"], False),  # a flag is no value
    ("run", ["--frames", "1-10", *JOB, "--objects", "--mode"], False),
    ("run", ["--frames", "1-10", *JOB, "--viewport=yes"], False),
    ("run", ["--frames", "1-10", *JOB, "--save", "x.blend"], True),  # not run's: passed on
    ("run", ["--frame", "1-10", *JOB], True),  # a flag's unambiguous abbreviation, as argparse takes it
    ("assemble", JOB, True),
    ("assemble", [*JOB, "--objects", "Torus", "--resolution", "64", "--voxel-size", "0.25"], True),
    ("assemble", [*JOB, "--save", "/out/x.blend", "--blend", "scene.blend", "--viewport"], True),
    ("assemble", [*JOB, "--frames", "1-10"], False),  # run's, not assemble's
    ("assemble", [*JOB, "--mode", "solid"], False),
    ("assemble", [*JOB, "stray"], False),
    ("assemble", ["--output", "/out"], False),
    ("assemble", [*JOB, "--resolution", "many"], False),
    ("assemble", [*JOB, "--save"], False),
]


def accepts(command, args):
    try:
        with contextlib.redirect_stderr(io.StringIO()):
            arguments.parse(command, args, TABLE)
    except (SystemExit, ValueError):
        return False
    return True


@pytest.mark.parametrize("command, args, accepted", CASES)
def test_the_parser_accepts_and_refuses(command, args, accepted):
    assert accepts(command, args) == accepted


def test_refusals_name_the_flag():
    for args, message in (
        (JOB, "the following arguments are required: --frames"),
        (["--frames", "1", "--job-frames", "1"], "the following arguments are required: --output/-o"),
        (["--frames", "1", *JOB, "-r", "x"], "argument --resolution/-r: invalid int value: 'x'"),
        (["--frames", "1", *JOB, "--blend"], "argument --blend: expected one argument"),
    ):
        stderr = io.StringIO()
        with contextlib.redirect_stderr(stderr), pytest.raises(SystemExit):
            arguments.parse("run", args, TABLE)
        assert stderr.getvalue().rstrip().endswith("error: " + message), stderr.getvalue()
    with pytest.raises(ValueError, match="^assemble does not take --mode solid$"):
        arguments.parse("assemble", [*JOB, "--mode", "solid"], TABLE)


def test_the_task_reads_what_the_flags_mean():
    known, rest = arguments.parse("run", ["--frames", "1-10", *JOB, "-r", "64", "--mode", "solid"], TABLE)
    assert (known.frames, known.job_frames, known.output, known.objects) == ("1-10", "1-250", "/out", "")
    assert (known.resolution, known.voxel_size, known.viewport, known.blend) == (64, 0.0, False, None)
    assert rest == ["--mode", "solid"]
    known, rest = arguments.parse("assemble", [*JOB, "--voxel-size", "0.5", "--save", "s.blend"], TABLE)
    assert (known.voxel_size, known.resolution, known.save, rest) == (0.5, None, "s.blend", [])
