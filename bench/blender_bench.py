# SPDX-License-Identifier: GPL-3.0-or-later
"""What the benchmarks that run in Blender (`blender -b --python`, or the bpy module) share:
Blender's Mesh to Volume modifier, set up the one way hyvox is timed against it, and the
end of the script, where a failure must not read as a finished run.

    if __name__ == "__main__":
        exit_1_on_error(main)
"""

import os
import sys
import traceback

import bpy


def mesh_to_volume(source, voxel_size):
    """A new volume object "MeshToVolume" with Blender's Mesh to Volume modifier on `source`:
    `voxel_size` and a band of one voxel inside (its default band, 0.2, is in world units).
    Returns the object and the modifier, for a benchmark's own settings on top."""
    volume = bpy.data.volumes.new("MeshToVolume")
    target = bpy.data.objects.new("MeshToVolume", volume)
    bpy.context.scene.collection.objects.link(target)
    modifier = target.modifiers.new("MeshToVolume", "MESH_TO_VOLUME")
    modifier.object = source
    modifier.resolution_mode = "VOXEL_SIZE"
    modifier.voxel_size = voxel_size
    modifier.interior_band_width = voxel_size
    return target, modifier


def exit_1_on_error(main):
    """main(); if it raises, its traceback and an exit with status 1 at once: Blender goes on
    after a --python script that raised, and exits 0, and os._exit leaves no exit handler of
    Blender's or bpy's to turn the failure into 0."""
    try:
        main()
    except Exception:
        traceback.print_exc()
        sys.stdout.flush()
        os._exit(1)
