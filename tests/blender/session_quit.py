# SPDX-License-Identifier: GPL-3.0-or-later
"""For test_save_moves_results: a Blender session that enables the add-on from ADDON_PARENT,
voxelizes a cube into its unsaved folder, saves to BLEND unless it is "unsaved", prints
"SESSION <unsaved|saved> <its folder>" and quits as Blender quits (atexit handlers run).

    blender -b --factory-startup --python session_quit.py -- ADDON_PARENT unsaved|BLEND"""
import sys

import addon_utils
import bpy

parent, blend = sys.argv[sys.argv.index("--") + 1:][:2]
sys.path.insert(0, parent)
addon_utils.enable("hyvox_blender", default_set=True, handle_error=None)
from hyvox_blender.core import naming  # noqa: E402

bpy.ops.mesh.primitive_cube_add()
bpy.ops.object.hyvox_voxelize(resolution=8, method="cpu", output_dir="")
folder = naming.unsaved_output_dir(create=False)
if blend != "unsaved":
    bpy.ops.wm.save_as_mainfile(filepath=blend)
print("SESSION", "unsaved" if blend == "unsaved" else "saved", folder, flush=True)
