# SPDX-License-Identifier: GPL-3.0-or-later
"""hyvox: voxelize meshes into OpenVDB volumes with a native GPU/CPU voxelizer.

Only registration lives here, and the entry point the render-farm jobs call (farm_main). bpy is imported inside register() so that the bpy-free
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


def farm_main(argv):
    """The entry point of the farm jobs (`hyvox job-template`): their Blender enables this
    add-on by its name and calls farm_main with the arguments after "--", so a job knows
    nothing of the add-on's inside. A farm command (run, assemble, serve), see farm/."""
    from . import farm

    farm.main(argv)
