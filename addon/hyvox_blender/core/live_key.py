# SPDX-License-Identifier: GPL-3.0-or-later
"""What a Live run's voxels depend on, as one key: the evaluated geometry and colour of
every group (the exported arrays, bit for bit) and the options (the settings a run uses,
the voxel size the volume keeps included). Equal keys give equal voxels, so a key is what
the cache is looked up by and how an update that changed nothing is told apart from one
that did: a frame of a static scene, an undo step back to a state seen before, a material
edit that the colour does not show."""

import hashlib
import json
from typing import Any, Iterable, Mapping

import numpy as np


def options_fingerprint(options: Mapping[str, Any]) -> str:
    """The options as canonical text (sorted, JSON): equal options, equal text."""
    return json.dumps(dict(options), sort_keys=True, default=str)


def _add_array(digest, array: np.ndarray) -> None:
    array = np.ascontiguousarray(array)
    digest.update(f"{array.dtype.str}{array.shape}".encode())
    digest.update(memoryview(array).cast("B"))  # hashlib releases the GIL on large buffers


def geometry_digest(meshes: Iterable) -> str:
    """A hex digest of the groups' arrays (vertices, triangles, colour sources) of
    pipeline.GroupMesh objects (not imported: the pipeline digests with this module)."""
    digest = hashlib.sha256()  # with SHA extensions the fastest of hashlib here
    for mesh in meshes:
        digest.update(mesh.group.key.encode() + b"\0")
        _add_array(digest, mesh.vertices)
        _add_array(digest, mesh.triangles)
        for name in sorted(mesh.colour):
            value = mesh.colour[name]
            digest.update(name.encode() + b"\0")
            if isinstance(value, np.ndarray):
                _add_array(digest, value)
            else:
                digest.update(repr(value).encode())
    return digest.hexdigest()


def run_key(geometry: str, fingerprint: str) -> str:
    """The key of a run: its geometry digest under its options."""
    return hashlib.sha256((geometry + "\0" + fingerprint).encode()).hexdigest()
