# SPDX-License-Identifier: GPL-3.0-or-later
# Ctrl-C (SIGINT) and SIGTERM while the CLI reads a large mesh: it stops within the reading,
# exits with the documented status 130 and "interrupted; nothing was written", and leaves
# neither the output nor a temporary file behind. The signal is sent when the CLI's own
# progress line says it is reading (an event, not a sleep).
import gzip
import re
import signal
import subprocess

import numpy as np
import pytest

PROGRESS = re.compile(r"hyvox: (\w+(?: \w+)?) +(\d+)%")


@pytest.fixture(scope="module")
def big_gzip(tmp_path_factory):
    """A 200 MB binary PLY (8M vertices, 8M triangles) as a 2 MB .ply.gz: decompressing and
    parsing it takes a good fraction of a second even on a fast machine. Made quickly as
    gzip members (one block, compressed once, repeated), which the reader takes as one file."""
    rows, block = 8 * 2**20, 2**16
    i = np.arange(block) % 1024  # a 32 x 32 height field, repeated: it compresses well
    vertices = np.stack([i % 32, i // 32, (i * 7) % 5], axis=1).astype("<f4")
    faces = np.zeros(block, dtype=[("n", "u1"), ("i", "<i4", 3)])
    faces["n"] = 3
    faces["i"] = np.stack([i, (i + 1) % 1024, (i + 32) % 1024], axis=1)
    header = (
        f"ply\nformat binary_little_endian 1.0\nelement vertex {rows}\nproperty float x\n"
        f"property float y\nproperty float z\nelement face {rows}\n"
        "property list uchar int vertex_indices\nend_header\n"
    ).encode()
    path = tmp_path_factory.mktemp("big_mesh") / "big.ply.gz"
    with open(path, "wb") as out:
        out.write(gzip.compress(header))
        for data in (vertices.tobytes(), faces.tobytes()):
            member = gzip.compress(data)
            for _ in range(rows // block):
                out.write(member)
    return path


@pytest.mark.parametrize("signal_number", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_signal_while_reading_stops_cleanly(cli, big_gzip, tmp_path, signal_number):
    output = tmp_path / "out.vdb"
    process = subprocess.Popen(
        [str(cli), "voxelize", str(big_gzip), "-o", str(output), "--progress", "--resolution", "256"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        lines = []
        for line in process.stderr:  # one line per percent (stderr is a pipe)
            lines.append(line.rstrip("\n"))
            match = PROGRESS.fullmatch(lines[-1])
            if match and match.group(1) == "read mesh" and 0 < int(match.group(2)) < 100:
                break  # reading, and well under way
        else:
            pytest.fail(f"the CLI never reported reading: {lines}")
        process.send_signal(signal_number)
        stdout, rest = process.communicate(timeout=120)
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()
    lines += rest.splitlines()
    assert process.returncode == 130, lines
    assert lines[-1] == "hyvox: error: interrupted; nothing was written", lines
    # It stopped within the reading: no later stage began.
    stages = {PROGRESS.fullmatch(line).group(1) for line in lines[:-1] if PROGRESS.fullmatch(line)}
    assert stages == {"read mesh"}, lines
    assert stdout == ""
    assert list(tmp_path.iterdir()) == []  # neither the .vdb nor a temporary file
