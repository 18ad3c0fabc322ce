# SPDX-License-Identifier: GPL-3.0-or-later
"""Where voxels are in the world, and the correction Blender's renderers need.

hyvox files keep OpenVDB's convention: index (i,j,k) is the voxel centre, at world
origin + (i + 1/2, j + 1/2, k + 1/2) * s (grid transform: scale s, translation origin + s/2).
Blender 3.4's Cycles and EEVEE sample voxel i over [i, i+1) in index space, i.e. they draw
every voxel half a voxel towards +x+y+z. We leave the file standard (other tools read it
right) and move the Volume object by -s/2 on each axis for the Blender versions that
need it. The headless render test measures this on the Blender it runs in."""

from typing import Sequence, Tuple

# First Blender version that renders voxel centres where OpenVDB puts them: 3.4 and 4.5 draw
# a cube's edges half a voxel off without the correction, 5.0 within a small fraction of a
# voxel. Measured by tests/blender/test_render_alignment.py; the figures per version:
# docs/blender-quirks.md. The add-on preference "Half-Voxel Fix" forces the correction on or
# off regardless.
FIRST_CENTRED_VERSION = (5, 0, 0)


def needs_half_voxel_shift(version: Sequence[int], override: str = "AUTO") -> bool:
    if override == "ON":
        return True
    if override == "OFF":
        return False
    return tuple(version[:3]) < FIRST_CENTRED_VERSION


def object_offset(voxel_size: float, version: Sequence[int], override: str = "AUTO") -> Tuple[float, float, float]:
    """World-space translation for the Volume object (its only transform)."""
    if not needs_half_voxel_shift(version, override):
        return (0.0, 0.0, 0.0)
    half = -0.5 * float(voxel_size)
    return (half, half, half)


# EEVEE Next (Blender 4.2-4.5) draws a Volume only inside the object's bounds, and those
# Blender computes from the grid's active 8^3 leaves with the last index taken as a point:
# the bounds end where the top leaf's last voxel layer begins, as 4.x draws voxel i over
# [i, i+1). Voxels in that layer (an object's +x/+y/+z side whenever its extent is a
# multiple of 8 voxels, as at the usual resolutions) are drawn faint or not at all. No
# setting of the object, the Volume or the scene moves those bounds (those tried:
# docs/blender-quirks.md); active voxels of any grid of the Volume beyond them do. So for
# these versions the add-on gives the Volume object a Geometry Nodes modifier that adds a
# small second grid beyond the bounds (blender/volume/eevee_bounds.py); the file and its
# voxels stay the voxelization's. Cycles draws the layer whole either way; 5.0 bounds the
# grid by its voxels' faces and EEVEE draws it whole. Measured by tests/blender/test_render_alignment.py
# in 4.2, 4.4, 4.5 and 5.0 (the figures: docs/blender-quirks.md); 4.3.0's EEVEE draws no frame
# with a Volume in view, but its bounds end as in 4.5, so it is taken to clip as 4.2 and 4.4 do.
EEVEE_CLIPPING_VERSIONS = ((4, 2, 0), (5, 0, 0))  # [first, end)


def eevee_clips_last_voxel_layer(version: Sequence[int]) -> bool:
    first, end = EEVEE_CLIPPING_VERSIONS
    return first <= tuple(version[:3]) < end
