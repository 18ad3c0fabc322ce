# SPDX-License-Identifier: GPL-3.0-or-later
"""The Scene's voxelize settings (scene.hyvox) and the add-on preferences. The operator
declares the same names so scripts can override any of them for one call."""
import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

from ..core import settings as core_settings

METHOD_ITEMS = [
    ("auto", "Auto", "Hybrid GL voxelizer when OpenGL 4.5 works on this machine, else CPU"),
    ("hybrid", "Hybrid (GPU)", "Triangle- and fragment-parallel passes split by triangle size (exact)"),
    ("triangle", "Triangle (GPU)", "One GPU thread per triangle (exact; best for many small triangles)"),
    ("fragment", "Fragment (GPU)", "Rasterized, one fragment per voxel column (exact; best for large triangles)"),
    ("tessellation", "Tessellation (GPU)", "Adaptive point tessellation (approximate, fast; may miss a few voxels)"),
    ("cpu", "CPU", "Exact multi-threaded CPU voxelizer (no GPU needed)"),
    ("reference", "Reference", "Brute-force exact oracle (slow; for checking results)"),
]
MODE_ITEMS = [
    ("conservative", "Conservative", "Every voxel the surface touches (26-separating)"),
    ("thin", "Thin", "The thinnest surface that still separates inside from outside (6-separating)"),
]
SIZE_ITEMS = [
    ("RESOLUTION", "Resolution", "Number of voxels along the longest side of the bounds"),
    ("VOXEL_SIZE", "Voxel Size", "Size of one voxel in scene units"),
]

# Shared definitions: the Scene group and the operator must not drift apart.
def resolution_prop(**kw):
    return IntProperty(name="Resolution", description="Voxels along the longest side of the bounding box",
                       default=256, min=core_settings.MIN_RESOLUTION, max=core_settings.MAX_RESOLUTION,
                       soft_min=8, soft_max=2048, subtype="NONE", **kw)


def voxel_size_prop(**kw):
    return FloatProperty(name="Voxel Size", description="Edge length of one voxel",
                         default=0.05, min=1e-6, soft_min=1e-4, soft_max=10.0, precision=4,
                         step=1, subtype="DISTANCE", unit="LENGTH", **kw)


def method_prop(**kw):
    return EnumProperty(name="Method", description="Voxelization algorithm", items=METHOD_ITEMS,
                        default="auto", **kw)


def mode_prop(**kw):
    return EnumProperty(name="Mode", description="Which voxels count as touched by the surface",
                        items=MODE_ITEMS, default="conservative", **kw)


def gamma_prop(**kw):
    return FloatProperty(name="Tessellation γ", description="Safety factor of the tessellation level: "
                         "higher misses fewer voxels and costs more points", default=1.0,
                         min=0.1, max=16.0, soft_min=0.5, soft_max=4.0, subtype="FACTOR", **kw)


def cutoff_prop(**kw):
    return FloatProperty(name="Cutoff", description="Projected triangle area (voxels²) above which "
                         "the hybrid method rasterizes a triangle", default=16.0, min=0.0,
                         soft_max=4096.0, subtype="NONE", **kw)


def separate_prop(**kw):
    return BoolProperty(name="One Volume per Object", description="Make one volume for every selected "
                        "object instead of one for the whole selection", default=False, **kw)


def output_dir_prop(**kw):
    return StringProperty(name="Output Folder", description="Where the .vdb files go; empty: a "
                          "hyvox_cache folder next to the .blend, or the temp folder if unsaved",
                          default="", subtype="DIR_PATH", **kw)


class HyvoxSceneSettings(bpy.types.PropertyGroup):
    size_mode: EnumProperty(name="Size", description="Set the grid by resolution or by voxel size",
                            items=SIZE_ITEMS, default="RESOLUTION")
    resolution: resolution_prop()
    voxel_size: voxel_size_prop()
    method: method_prop()
    mode: mode_prop()
    tessellation_gamma: gamma_prop()
    hybrid_cutoff_auto: BoolProperty(name="Auto Cutoff", description="Let the hybrid method find the "
                                     "fastest cutoff for this mesh and resolution", default=True)
    hybrid_cutoff: cutoff_prop()
    separate: separate_prop()
    padding: IntProperty(name="Padding", description="Empty voxels added around the bounds",
                         default=0, min=0, max=64, subtype="NONE")
    output_dir: output_dir_prop()
    use_frame_range: BoolProperty(name="Frame Range", description="Voxelize every frame of a range into "
                                  "a .vdb sequence", default=False)
    frame_start: IntProperty(name="Start", description="First frame of the sequence", default=1,
                             min=0, subtype="TIME")
    frame_end: IntProperty(name="End", description="Last frame of the sequence", default=250,
                           min=0, subtype="TIME")


ADDON_NAME = __package__.rpartition(".")[0]


class HyvoxPreferences(bpy.types.AddonPreferences):
    bl_idname = ADDON_NAME

    gl_device: EnumProperty(name="GPU Device", description="EGL device the GL methods run on",
                            items=[("AUTO", "Automatic", "A hardware GPU if there is one, else software"),
                                   ("SOFTWARE", "Software", "Mesa's llvmpipe (slow; always works)"),
                                   ("INDEX", "By Index", "The EGL device with the index below")],
                            default="AUTO")
    gl_device_index: IntProperty(name="Device Index", description="Index of the EGL device to use",
                                 default=0, min=0, max=63, subtype="NONE")
    memory_budget_mb: IntProperty(name="Memory Budget (MiB)", description="Largest voxel grid "
                                  "(one bit per voxel) to allocate; bigger requests are refused",
                                  default=4096, min=16, max=1 << 20, subtype="UNSIGNED")
    alignment_fix: EnumProperty(name="Half-Voxel Fix", description="Move volumes by half a voxel to "
                                "match how this Blender draws OpenVDB voxel centres",
                                items=[("AUTO", "Automatic", "By Blender version"),
                                       ("ON", "On", "Always correct"),
                                       ("OFF", "Off", "Never correct")], default="AUTO")

    def draw(self, context):
        layout = self.layout
        row = layout.row()
        row.prop(self, "gl_device")
        sub = row.row()
        sub.enabled = self.gl_device == "INDEX"
        sub.prop(self, "gl_device_index")
        layout.prop(self, "memory_budget_mb")
        layout.prop(self, "alignment_fix")

    @property
    def gl_device_string(self) -> str:
        return {"AUTO": "", "SOFTWARE": "software"}.get(self.gl_device, str(self.gl_device_index))


def preferences(context):
    addon = context.preferences.addons.get(ADDON_NAME)
    return addon.preferences if addon is not None else None


CLASSES = (HyvoxSceneSettings, HyvoxPreferences)


def register():
    bpy.types.Scene.hyvox = bpy.props.PointerProperty(type=HyvoxSceneSettings)


def unregister():
    del bpy.types.Scene.hyvox
