# SPDX-License-Identifier: GPL-3.0-or-later
"""hyvox: voxelize meshes into OpenVDB volumes with a native GPU/CPU voxelizer.

Only registration lives here. bpy is imported inside register() so that the bpy-free
layer (hyvox_blender.core) can be imported by pytest and pipelines outside Blender."""

bl_info = {
    "name": "hyvox Voxelizer",
    "author": "hyvox developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "View3D > Sidebar > Voxelize; Object > Voxelize",
    "description": "Voxelize selected meshes into aligned OpenVDB volumes (GPU hybrid or exact CPU)",
    "category": "Object",
    "support": "COMMUNITY",
}


def register():
    # Imported here, not above: the bpy layer imports bpy, and core/ must stay importable
    # without it (pytest, pipelines outside Blender).
    from .blender import registration

    registration.register()


def unregister():
    from .blender import registration  # (see register)

    registration.unregister()
