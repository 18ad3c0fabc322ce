# SPDX-License-Identifier: GPL-3.0-or-later
"""Run in a Blender that opened an assembled .blend: prints (PROBE + JSON) the volume
objects, their sequence settings and the file each frame plays."""

import json

import bpy

scene = bpy.context.scene
out = []
for obj in scene.objects:
    if obj.type != "VOLUME":
        continue
    volume = obj.data
    frames = {}
    for frame in range(1, 7):
        scene.frame_set(frame)
        evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get()).data
        frames[frame] = bpy.path.abspath(evaluated.grids.frame_filepath)
    out.append(
        {
            "name": obj.name,
            "is_sequence": volume.is_sequence,
            "frame_start": volume.frame_start,
            "frame_duration": volume.frame_duration,
            "materials": [m.name for m in volume.materials if m],
            "location": list(obj.location),
            "frames": frames,
        }
    )
print("PROBE " + json.dumps(out))
