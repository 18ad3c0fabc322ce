# SPDX-License-Identifier: GPL-3.0-or-later
"""The lattice fixed in world space, worked out in the tests (numpy), for the module's
snap_origin to be checked against: the origin at floor(min / voxel size) voxel sizes (one
lower where that product rounds above the min), the min of the vertices the triangles use.
The floor of the rounded quotient, as the add-on's lattice had it: frames and Live runs of
earlier versions land on the same voxels."""

import numpy as np


def snapped_origin(vertices, triangles, voxel_size):
    used = np.asarray(vertices, np.float64)[np.unique(np.asarray(triangles).reshape(-1))]
    low = used.min(axis=0)
    k = np.floor(low / voxel_size)
    k -= k * voxel_size > low  # a quotient that rounded up to a whole number
    return tuple(float(x) for x in k * voxel_size)
