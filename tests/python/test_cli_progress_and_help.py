# SPDX-License-Identifier: GPL-3.0-or-later
# The command line's progress line (stderr: on a terminal, forced by --progress, silenced by
# --quiet), its per-command help and its one-line usage errors.
import os
import pty
import re
import subprocess

import hyvox

PROGRESS = re.compile(r"hyvox: (\w+(?: \w+)?) +(\d+)%")


def run(cli, *args, **kwargs):
    return subprocess.run([str(cli), *map(str, args)], capture_output=True, text=True, timeout=300, **kwargs)


def stages(lines):
    """[(stage, [percent, ...]), ...] in the order the lines came."""
    out = []
    for line in lines:
        match = PROGRESS.fullmatch(line)
        assert match, f"not a progress line: {line!r}"
        stage, percent = match.group(1), int(match.group(2))
        if not out or out[-1][0] != stage:
            out.append((stage, []))
        out[-1][1].append(percent)
    return out


def check_stages(found):
    assert [stage for stage, _ in found] == ["read mesh", "voxelize", "write"]
    for stage, percents in found:
        assert percents == sorted(set(percents)), (stage, percents)  # rising, never repeated
        assert 0 <= percents[0] and percents[-1] == 100, (stage, percents)


def test_forced_progress_into_a_pipe_is_one_line_per_percent(cli, mesh_dir, tmp_path):
    out = tmp_path / "b.vdb"
    result = run(
        cli,
        "voxelize",
        mesh_dir / "bunny_stanford_69k.ply",
        "-o",
        out,
        "--resolution",
        128,
        "--method",
        "cpu",
        "--progress",
    )
    assert result.returncode == 0, result.stderr
    assert "\r" not in result.stderr and result.stderr.endswith("100%\n")
    found = stages(result.stderr.splitlines())
    check_stages(found)
    assert len(found[1][1]) > 2  # the exact method reports within the run, not only its ends
    assert "voxels" in result.stdout and out.exists()


def test_quiet_prints_nothing_and_no_progress_without_a_terminal(cli, mesh_dir, tmp_path):
    mesh = mesh_dir / "teapot_utah.ply"
    quiet = run(cli, "voxelize", mesh, "-o", tmp_path / "q.vdb", "--resolution", 64, "-q")
    assert quiet.returncode == 0 and quiet.stdout == "" and quiet.stderr == ""
    plain = run(cli, "voxelize", mesh, "-o", tmp_path / "p.vdb", "--resolution", 64)
    assert plain.returncode == 0 and plain.stderr == ""  # stderr is a pipe here: no progress
    both = run(cli, "voxelize", mesh, "-o", tmp_path / "c.vdb", "--progress", "--quiet")
    assert both.returncode == 2 and "contradict" in both.stderr


def run_on_terminal(cli, *args):
    """(status, what stderr showed) with stderr a pseudo-terminal."""
    leader, follower = pty.openpty()
    try:
        process = subprocess.Popen([str(cli), *map(str, args)], stdout=subprocess.DEVNULL, stderr=follower)
        os.close(follower)
        shown = b""
        while True:
            try:
                chunk = os.read(leader, 65536)
            except OSError:  # EIO: the process closed its end
                break
            if not chunk:
                break
            shown += chunk
        return process.wait(timeout=300), shown.decode()
    finally:
        os.close(leader)


def test_progress_on_a_terminal_rewrites_one_line_per_stage(cli, mesh_dir, tmp_path):
    status, shown = run_on_terminal(
        cli,
        "voxelize",
        mesh_dir / "bunny_stanford_69k.ply",
        "-o",
        tmp_path / "t.vdb",
        "--resolution",
        128,
        "--method",
        "cpu",
    )
    assert status == 0, shown
    shown = shown.replace("\r\n", "\n")  # the terminal's own newline translation
    lines = shown.split("\n")
    assert lines[-1] == "" and len(lines) == 4, shown  # one line per stage, each finished
    found = [stages(line.split("\r")[1:])[0] for line in lines[:3]]
    check_stages(found)
    status, shown = run_on_terminal(cli, "voxelize", mesh_dir / "teapot_utah.ply", "-o", tmp_path / "q.vdb", "-q")
    assert status == 0 and shown == ""


def test_help_per_command(cli):
    general = run(cli, "--help")
    assert general.returncode == 0 and general.stderr == ""
    assert "voxelize" in general.stdout and "gamma-sweep" in general.stdout
    assert not any(spec.cli_flag in general.stdout for spec in hyvox.OPTIONS)  # commands only

    voxelize = run(cli, "voxelize", "--help")
    assert voxelize.returncode == 0 and voxelize.stdout.startswith("usage: hyvox voxelize")
    for flag in [spec.cli_flag for spec in hyvox.OPTIONS] + ["--output", "--progress", "--quiet"]:
        assert re.search(rf"^  (-\w, )?{flag}\b", voxelize.stdout, re.M), flag
    assert "--gammas" not in voxelize.stdout

    sweep = run(cli, "gamma-sweep", "--help")
    assert sweep.returncode == 0 and sweep.stdout.startswith("usage: hyvox gamma-sweep")
    assert "--gammas" in sweep.stdout and "--output" not in sweep.stdout
    for flag in ("--method", "--mode", "--tess-gamma"):  # the sweep sets these itself
        assert f"  {flag} " not in sweep.stdout, flag
    assert "  --resolution" in sweep.stdout


def test_usage_error_is_one_line_and_a_hint(cli, mesh_dir):
    for args, hint in [
        (["voxelize", mesh_dir / "teapot_utah.ply", "--bogus"], "hyvox voxelize --help"),
        (["gamma-sweep", "--gammas", "2"], "hyvox gamma-sweep --help"),
        (["frobnicate"], "hyvox --help"),
    ]:
        result = run(cli, *args)
        lines = result.stderr.splitlines()
        assert result.returncode == 2 and result.stdout == ""
        assert len(lines) == 2 and lines[0].startswith("hyvox: error: "), result.stderr
        assert hint in lines[1]
