# SPDX-License-Identifier: GPL-3.0-or-later
"""Damaged mesh files and what hyvox's three front doors make of them.

Damage (each from a seed, so every case can be made again):
  truncate  the file cut at a random place (anywhere, near its start, near its end, at the end
            of a line);
  flip      1 to 8 bytes set to random values;
  count     a number the file declares (a vertex, triangle or index count, a byte length or
            offset; where the format puts them: count_sites()) set to another value;
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
import re
import struct
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "python"))
import mesh_writers  # noqa: E402, F401  (damage_meshes.py takes it from here)

KINDS = ("truncate", "flip", "count", "splice")


def _text_numbers(data, start, end, keys=None):
    """(offset, length, value, "text") of the whole decimal numbers in data[start:end]; with
    `keys`, only those that follow one of them (a JSON member: "count": 24)."""
    sites = []
    if keys is None:
        pattern, group = rb"(?<![0-9.eE+-])[0-9]+(?![0-9.eE])", 0
    else:
        pattern, group = rb'"(?:' + b"|".join(keys) + rb')"\s*:\s*([0-9]+)', 1
    for match in re.finditer(pattern, data[start:end]):
        sites.append(
            (start + match.start(group), match.end(group) - match.start(group), int(match.group(group)), "text")
        )
    return sites


def _fbx_sites(data):
    """The FBX container's declared sizes: record end offsets and property byte counts, and
    each array's count and stored length."""
    sites = []
    wide = struct.unpack_from("<I", data, 23)[0] >= 7500
    size, fmt, encoding = (8, "<Q", "u64") if wide else (4, "<I", "u32")
    array_kinds = (b"d", b"l", b"i", b"f", b"b", b"c")
    scalar_bytes = {b"C": 1, b"Y": 2, b"I": 4, b"F": 4, b"D": 8, b"L": 8}

    def walk(at, end, depth):
        while at + 3 * size + 1 <= end and depth < 32:
            record_end, properties, property_bytes = (struct.unpack_from(fmt, data, at + k * size)[0] for k in range(3))
            if record_end == 0:
                return
            sites.extend([(at, size, record_end, encoding), (at + 2 * size, size, property_bytes, encoding)])
            p = at + 3 * size + 1 + data[at + 3 * size]
            for _ in range(properties):
                kind = data[p : p + 1]
                if kind in array_kinds:
                    sites.extend(
                        [
                            (p + 1, 4, struct.unpack_from("<I", data, p + 1)[0], "u32"),
                            (p + 9, 4, struct.unpack_from("<I", data, p + 9)[0], "u32"),
                        ]
                    )
                    p += 13 + struct.unpack_from("<I", data, p + 9)[0]
                elif kind in (b"S", b"R"):
                    p += 5 + struct.unpack_from("<I", data, p + 1)[0]
                else:
                    p += 1 + scalar_bytes[kind]
            if p < record_end:
                walk(p, record_end, depth + 1)
            at = record_end

    walk(27, len(data), 0)
    return sites


def _zip_sites(data):
    """A zip's declared entry sizes, in its local headers and its central directory."""
    sites = []
    for signature, sizes_at in ((b"PK\x03\x04", 18), (b"PK\x01\x02", 20)):
        at = data.find(signature)
        while at >= 0:
            for k in range(2):
                sites.append(
                    (at + sizes_at + 4 * k, 4, struct.unpack_from("<I", data, at + sizes_at + 4 * k)[0], "u32")
                )
            at = data.find(signature, at + 4)
    return sites


def count_sites(format_name, data):
    """(offset, length, value, encoding) of every count or size the file declares (not the
    values of its data): what "count" damage changes. OBJ and ASCII STL declare none."""
    gltf_keys = [b"count", b"byteLength", b"byteOffset", b"byteStride"]
    if format_name == "ply":
        return _text_numbers(data, 0, data.index(b"end_header"))
    if format_name == "off":
        third_line = data.index(b"\n", data.index(b"\n", data.index(b"\n") + 1) + 1)
        return _text_numbers(data, 0, third_line)
    if format_name == "stl_binary":
        return [(80, 4, struct.unpack_from("<I", data, 80)[0], "u32")]
    if format_name == "gltf":
        return _text_numbers(data, 0, len(data), gltf_keys)
    if format_name == "glb":
        json_length = struct.unpack_from("<I", data, 12)[0]
        container = [(8, 4, struct.unpack_from("<I", data, 8)[0], "u32"), (12, 4, json_length, "u32")]
        if len(data) >= 24 + json_length:
            container.append((20 + json_length, 4, struct.unpack_from("<I", data, 20 + json_length)[0], "u32"))
        return container + _text_numbers(data, 20, 20 + json_length, gltf_keys)
    if format_name == "fbx":
        return _fbx_sites(data)
    if format_name == "3mf":
        return _zip_sites(data)
    return []


def damaged(format_name, data, vertices, triangles, kind, rng, others=()):
    """One damaged copy of `data`: (bytes, note). `others`: files of the same format to take
    splice pieces from."""
    size = len(data)
    if kind == "truncate":
        # A cut at a line's end is the one a text reader most easily takes for the file's end.
        where = rng.choice(("anywhere", "start", "end", "line"))
        if where == "line":
            newline = data.find(b"\n", rng.randrange(size))
            cut = newline + 1 if 0 <= newline < size - 1 else rng.randrange(size)
        else:
            cut = {
                "anywhere": lambda: rng.randrange(size),
                "start": lambda: rng.randrange(min(size, 256)),
                "end": lambda: max(0, size - 1 - rng.randrange(min(size, 64))),
            }[where]()
        return data[:cut], {"cut": cut, "size": size, "where": where}
    if kind == "flip":
        out = bytearray(data)
        places = [rng.randrange(size) for _ in range(rng.randint(1, 8))]
        for p in places:
            out[p] = rng.randrange(256)
        return bytes(out), {"bytes": places}
    if kind == "count":
        sites = count_sites(format_name, data)
        if not sites:
            return None, {"no count": True}
        offset, length, value, encoding = rng.choice(sites)
        new = rng.choice([value - 1, value + 1, 2 * value, value // 2, 0, 2**31 - 1, 2**32 - 1, value * 1000 + 7])
        new = max(new, 0)
        if encoding == "text":
            piece = str(new).encode()
        else:
            new = min(new, 2 ** (8 * length) - 1)
            piece = new.to_bytes(length, "little")
        return data[:offset] + piece + data[offset + length :], {
            "at": offset,
            "was": value,
            "now": new,
            "encoding": encoding,
        }
    # splice
    source = rng.choice(list(others) + [data]) if others else data
    a = rng.randrange(len(source))
    piece = source[a : a + rng.randint(1, 512)]
    at = rng.randrange(size)
    if rng.random() < 0.5:
        return data[:at] + piece + data[at:], {"insert": at, "bytes": len(piece)}
    return data[:at] + piece + data[at + len(piece) :], {"overwrite": at, "bytes": len(piece)}


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
        done = subprocess.run(
            [cli, "voxelize", path, "-o", out, "--resolution", "8", "--method", "cpu", "-q", "--stats-json", stats],
            capture_output=True,
            text=True,
            timeout=CLI_SECONDS,
        )
    except subprocess.TimeoutExpired:
        return {"outcome": "failure", "why": f"no end within {CLI_SECONDS} s"}
    return _cli_outcome(done, stats)


def gamma_sweep_door(cli, path, work):
    try:
        done = subprocess.run(
            [cli, "gamma-sweep", path, "--gammas", "1,2", "--resolution", "8", "-q"],
            capture_output=True,
            text=True,
            timeout=CLI_SECONDS,
        )
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
        return {"outcome": "error", "message": lines[-1][len("hyvox: error: ") :]}
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
        self.worker = subprocess.Popen(
            [sys.executable, "-c", WORKER, HERE],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            env=self.env,
        )

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
        problems.append(
            f"the doors disagree: {kinds} "
            + "; ".join(f"{n}: {o.get('message', '')}" for n, o in doors.items() if o["outcome"] == "error")
        )
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
            problems.append(
                f"a changed count ({note['was']} -> {now} at byte {note['at']}) read as a mesh of "
                f"{module['triangles']} triangles, {module['vertices']} vertices"
            )
    return problems
