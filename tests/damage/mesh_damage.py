# SPDX-License-Identifier: GPL-3.0-or-later
"""Damaged mesh files and what hyvox's three front doors make of them.

Damage (each from a seed, so every case can be made again):
  truncate  the file cut at a random place (anywhere, near its start, near its end);
  flip      1 to 8 bytes set to random values;
  count     a number the file declares (a vertex, triangle or index count, a byte length; in
            text or as a 32-bit little-endian integer) set to another value;
  splice    a piece of this file or of another file of the same format inserted, or
            written over a piece of this one.

Doors: the CLI (`hyvox voxelize`, resolution 8, cpu), the module (`hyvox.read_mesh` and
`hyvox.voxelize` in a worker subprocess, so that a crash is seen and not suffered) and
`hyvox gamma-sweep` (resolution 8, gammas 1 and 2). Each door's outcome is "ok" (with the
mesh's triangle count and voxel count), "error" (with the message), or a failure: a signal,
another exit status, a worker that died, a time limit passed.

Judged (judge()): every door ends with ok or error, all three the same way (the same
message; the same triangle and voxel counts); no partial result: a cut file read as a mesh
must be the whole mesh (an OBJ, which has no end marker, the mesh of the lines left: the
original's triangles but possibly the last), and a changed count read as a mesh must be the
whole mesh or have exactly the count written."""
import hashlib
import json
import os
import random
import re
import struct
import subprocess
import sys
import zipfile
import io

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "python"))
import mesh_writers  # noqa: E402

KINDS = ("truncate", "flip", "count", "splice")


def counts_in(format_name, data, vertices, triangles):
    """The values the file declares that damage may change: {value: what it counts}."""
    n, m = len(vertices), len(triangles)
    values = {n: "vertices", m: "triangles", 3 * m: "indices", 3 * n: "coordinates", 12 * n: "bytes",
              12 * m: "bytes"}
    if format_name == "3mf":  # a zip: its entries' sizes
        with zipfile.ZipFile(io.BytesIO(data)) as z:
            for info in z.infolist():
                values.setdefault(info.compress_size, "zip sizes")
                values.setdefault(info.file_size, "zip sizes")
    return {v: what for v, what in values.items() if v > 1}


def _count_sites(data, counts):
    """(offset, length, value, encoding) of every place a count appears: a whole decimal
    number in text, or a little-endian uint32."""
    sites = []
    for match in re.finditer(rb"(?<![0-9.eE+-])[0-9]+(?![0-9.eE])", data):
        value = int(match.group())
        if value in counts:
            sites.append((match.start(), match.end() - match.start(), value, "text"))
    for value in counts:
        if value < 1 << 32:
            packed = struct.pack("<I", value)
            start = data.find(packed)
            while start >= 0 and len(sites) < 10000:
                sites.append((start, 4, value, "u32"))
                start = data.find(packed, start + 1)
    return sites


def damaged(format_name, data, vertices, triangles, kind, rng, others=()):
    """One damaged copy of `data`: (bytes, note). `others`: files of the same format to take
    splice pieces from."""
    size = len(data)
    if kind == "truncate":
        where = rng.choice(("anywhere", "start", "end"))
        cut = {"anywhere": lambda: rng.randrange(size), "start": lambda: rng.randrange(min(size, 256)),
               "end": lambda: max(0, size - 1 - rng.randrange(min(size, 64)))}[where]()
        return data[:cut], {"cut": cut, "size": size}
    if kind == "flip":
        out = bytearray(data)
        places = [rng.randrange(size) for _ in range(rng.randint(1, 8))]
        for p in places:
            out[p] = rng.randrange(256)
        return bytes(out), {"bytes": places}
    if kind == "count":
        counts = counts_in(format_name, data, vertices, triangles)
        sites = _count_sites(data, counts)
        if not sites:
            return None, {"no count": True}
        offset, length, value, encoding = rng.choice(sites)
        new = rng.choice([value - 1, value + 1, 2 * value, value // 2, 0, 2**31 - 1, 2**32 - 1, value * 1000 + 7])
        new = max(new, 0)
        if encoding == "text":
            piece = str(new).encode()
        else:
            piece = struct.pack("<I", min(new, 2**32 - 1))
        return data[:offset] + piece + data[offset + length:], {
            "at": offset, "was": value, "now": new, "counts": counts[value], "encoding": encoding}
    # splice
    source = rng.choice(list(others) + [data]) if others else data
    a = rng.randrange(len(source))
    piece = source[a:a + rng.randint(1, 512)]
    at = rng.randrange(size)
    if rng.random() < 0.5:
        return data[:at] + piece + data[at:], {"insert": at, "bytes": len(piece)}
    return data[:at] + piece + data[at + len(piece):], {"overwrite": at, "bytes": len(piece)}


def corner_rows(vertices, triangles):
    """Each triangle as the 9 floats of its corners."""
    return np.asarray(vertices, np.float32)[np.asarray(triangles, np.int64)].reshape(-1, 9)


def digest(rows):
    """The triangles as a set-like fingerprint: the same triangles in any order and with any
    vertex numbering give the same digest."""
    rows = np.ascontiguousarray(rows, np.float32)
    order = np.lexsort(rows.T[::-1]) if len(rows) else np.zeros(0, int)
    return hashlib.sha1(rows[order].tobytes()).hexdigest()


# --- doors -------------------------------------------------------------------------------

CLI_SECONDS = 300  # far past the assimp process's own limit (60 s + 2 s a MiB)


def cli_door(cli, path, work):
    out, stats = os.path.join(work, "door.vdb"), os.path.join(work, "door.json")
    for f in (out, stats):
        if os.path.exists(f):
            os.remove(f)
    try:
        done = subprocess.run([cli, "voxelize", path, "-o", out, "--resolution", "8", "--method", "cpu", "-q",
                               "--stats-json", stats], capture_output=True, text=True, timeout=CLI_SECONDS)
    except subprocess.TimeoutExpired:
        return {"outcome": "failure", "why": f"no end within {CLI_SECONDS} s"}
    return _cli_outcome(done, stats)


def gamma_sweep_door(cli, path, work):
    try:
        done = subprocess.run([cli, "gamma-sweep", path, "--gammas", "1,2", "--resolution", "8", "-q"],
                              capture_output=True, text=True, timeout=CLI_SECONDS)
    except subprocess.TimeoutExpired:
        return {"outcome": "failure", "why": f"no end within {CLI_SECONDS} s"}
    return _cli_outcome(done, None)


def _cli_outcome(done, stats):
    if done.returncode == 0:
        result = {"outcome": "ok"}
        if stats:
            with open(stats) as f:
                s = json.load(f)
            result.update(triangles=s["triangles"]["input"], voxels=s["voxel_count"])
        return result
    lines = [line for line in done.stderr.splitlines() if line.startswith("hyvox: error: ")]
    if done.returncode == 1 and lines:
        return {"outcome": "error", "message": lines[-1][len("hyvox: error: "):]}
    return {"outcome": "failure", "why": f"exit status {done.returncode}", "stderr": done.stderr[-500:]}


WORKER = r"""
import hashlib, json, sys
import numpy as np
import hyvox
sys.path.insert(0, sys.argv[1])
import mesh_damage
originals = {}
for line in sys.stdin:
    job = json.loads(line)
    try:
        v, t = hyvox.read_mesh(job["path"])
        ok = bool(len(t)) and int(t.max(initial=0)) < len(v)
        rows = mesh_damage.corner_rows(v, t)
        result = {"outcome": "ok", "triangles": int(len(t)), "vertices": int(len(v)), "indices_in_range": ok,
                  "digest": mesh_damage.digest(rows)}
        if job.get("original"):
            if job["original"] not in originals:
                ov, ot = hyvox.read_mesh(job["original"])
                originals[job["original"]] = mesh_damage.corner_rows(ov, ot)
            whole = originals[job["original"]]
            # The lines an OBJ cut leaves: the original's triangles, in order, but the last.
            k = len(rows) - 1
            result["prefix"] = bool(0 <= k <= len(whole) and np.array_equal(rows[:k], whole[:k]))
        try:
            grid = hyvox.voxelize(v, t, resolution=8, method="cpu")
            result["voxels"] = int(grid.voxel_count)
        except ValueError as e:
            result = {"outcome": "error", "message": str(e)}
    except ValueError as e:
        result = {"outcome": "error", "message": str(e)}
    except Exception as e:
        result = {"outcome": "failure", "why": f"{type(e).__name__}: {e}"}
    print(json.dumps(result), flush=True)
"""


class ModuleDoor:
    """read_mesh + voxelize in a worker process that reads one job a line; a worker that dies
    is that file's failure (and a fresh one takes the next file)."""

    def __init__(self, pythonpath):
        self.env = {**os.environ, "PYTHONPATH": pythonpath}
        self.worker = None

    def _start(self):
        self.worker = subprocess.Popen([sys.executable, "-c", WORKER, HERE], stdin=subprocess.PIPE,
                                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=self.env)

    def __call__(self, path, original=None):
        if self.worker is None or self.worker.poll() is not None:
            self._start()
        self.worker.stdin.write(json.dumps({"path": path, "original": original}) + "\n")
        self.worker.stdin.flush()
        line = self.worker.stdout.readline()
        if not line:
            status = self.worker.wait()
            why = f"the worker died ({'signal %d' % -status if status < 0 else 'exit %d' % status})"
            self.worker = None
            return {"outcome": "failure", "why": why}
        return json.loads(line)

    def close(self):
        if self.worker is not None:
            self.worker.stdin.close()
            self.worker.wait(timeout=60)
            self.worker = None


# --- judging -----------------------------------------------------------------------------

def judge(format_name, kind, note, whole, cli, module, sweep):
    """The problems with one damaged file's outcomes ([] when there are none). `whole`: the
    undamaged file's module outcome."""
    problems = []
    doors = {"cli": cli, "module": module, "gamma-sweep": sweep}
    for name, outcome in doors.items():
        if outcome["outcome"] not in ("ok", "error"):
            problems.append(f"{name}: {outcome.get('why')} {outcome.get('stderr', '')}".strip())
    if problems:
        return problems
    kinds = {name: o["outcome"] for name, o in doors.items()}
    if len(set(kinds.values())) != 1:
        problems.append(f"the doors disagree: {kinds} " +
                        "; ".join(f"{n}: {o.get('message', '')}" for n, o in doors.items() if o["outcome"] == "error"))
        return problems
    if cli["outcome"] == "error":
        messages = {cli["message"], module["message"], sweep["message"]}
        if len(messages) != 1:
            problems.append(f"the doors' messages differ: {sorted(messages)}")
        return problems
    if not module["indices_in_range"]:
        problems.append("a triangle index past the vertices")
    if cli["triangles"] != module["triangles"] or cli["voxels"] != module["voxels"]:
        problems.append(f"cli and module read different meshes: {cli} {module}")
    same = module["digest"] == whole["digest"]
    if kind == "truncate" and not same and not (format_name == "obj" and module.get("prefix")):
        problems.append(f"a cut file read as another mesh ({module['triangles']} of {whole['triangles']} triangles)")
    if kind == "count" and not same:
        now = note["now"]
        if now not in (module["triangles"], module["vertices"], 3 * module["triangles"], 3 * module["vertices"]):
            problems.append(f"a changed count ({note['counts']} {note['was']} -> {now}) read as a mesh of "
                            f"{module['triangles']} triangles, {module['vertices']} vertices")
    return problems
