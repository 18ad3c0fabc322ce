# SPDX-License-Identifier: GPL-3.0-or-later
"""For test_save_moves_results: a Blender session that enables the add-on from ADDON_PARENT,
voxelizes a cube into its unsaved folder ("failed": a mesh without faces, so the folder is
made and stays empty), saves to BLEND unless it is "unsaved" or "failed", prints
"SESSION <unsaved|failed|saved> <its folder>" and quits as Blender quits (atexit handlers run).

    blender -b --factory-startup --python session_quit.py -- ADDON_PARENT unsaved|failed|BLEND"""

import sys

import addon_utils
import bpy

parent, blend = sys.argv[sys.argv.index("--") + 1 :][:2]
sys.path.insert(0, parent)
addon_utils.enable("hyvox_blender", default_set=True, handle_error=None)
from hyvox_blender.core import naming  # noqa: E402

bpy.ops.mesh.primitive_cube_add()
if blend == "failed":
    bpy.context.active_object.data.clear_geometry()
try:
    bpy.ops.object.hyvox_voxelize(resolution=8, method="cpu", output_dir="")
except RuntimeError as exc:  # the report of the failed run
    print("hyvox:", exc)
folder = naming.unsaved_output_dir(create=False)
if blend not in ("unsaved", "failed"):
    bpy.ops.wm.save_as_mainfile(filepath=blend)
print("SESSION", blend if blend in ("unsaved", "failed") else "saved", folder, flush=True)
