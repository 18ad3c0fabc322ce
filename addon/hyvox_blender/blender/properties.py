# SPDX-License-Identifier: GPL-3.0-or-later
"""The Scene's voxelize settings (scene.hyvox), the add-on preferences, and the builder both
they and the operator take their properties from.

Every property that stands for a hyvox option is made from the native options schema
(hyvox.OPTIONS): its name, description, default, limits and choices are the schema's, so
the add-on cannot drift from the CLI and the Python module. Blender's limits are inclusive:
an exclusive minimum (voxel size > 0) becomes min + EXCLUSIVE_STEP."""
import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

from ..core import backend

FLOAT_LIMIT = 3.4028234e38   # Blender float properties are float32
INT_LIMIT = 2**31 - 1        # ... and int properties int32
EXCLUSIVE_STEP = 1e-6

# How the choices of the schema's enums read in the UI; a choice missing here still
# appears, under its own name.
CHOICE_LABELS = {
    "method": {
        backend.AUTO_METHOD: ("Auto", "Hybrid GL voxelizer when a GPU runs OpenGL 4.5 here, else CPU"),
        "hybrid": ("Hybrid (GPU)", "Triangle- and fragment-parallel passes split by triangle size (exact)"),
        "triangle": ("Triangle (GPU)", "One GPU thread per triangle (exact; best for many small triangles)"),
        "fragment": ("Fragment (GPU)", "Rasterized, one fragment per voxel column (exact; best for large triangles)"),
        "tessellation": ("Tessellation (GPU)", "Adaptive point tessellation (approximate, fast; may miss a few voxels)"),
        "cpu": ("CPU", "Exact multi-threaded CPU voxelizer (no GPU needed)"),
        "reference": ("Reference", "Brute-force exact oracle (slow; for checking results)"),
    },
    "mode": {
        "conservative": ("Conservative", "Every voxel the surface touches (26-separating)"),
        "thin": ("Thin", "The thinnest surface that still separates inside from outside (6-separating)"),
        "solid": ("Solid", "The surface and every voxel whose centre is inside"),
    },
    "inside": {
        "auto": ("Auto", "The winding number: exact by rays for closed meshes, fast winding numbers for open ones"),
        "parity": ("Parity", "Inside where a ray crosses the surface an odd number of times (closed meshes)"),
        "winding": ("Winding Number", "Inside where the winding number is at least 0.5 (holes, flipped faces)"),
    },
}
SIZE_ITEMS = [
    ("RESOLUTION", "Resolution", "Number of voxels along the longest side of the bounds"),
    ("VOXEL_SIZE", "Voxel Size", "Size of one voxel in scene units"),
]


def option_spec(name):
    return backend.load_module().option(name)


def hard_limits(spec):
    """The schema's limits as Blender's inclusive, float32/int32 hard limits."""
    low = spec.min + (EXCLUSIVE_STEP if spec.min_exclusive else 0.0)
    bound = INT_LIMIT if spec.type == "int" else FLOAT_LIMIT
    return max(low, -bound), min(spec.max, bound)


def _description(spec):
    text = spec.help[:1].upper() + spec.help[1:]
    return f"{text} [{spec.unit}]" if spec.unit else text


def schema_property(name, operator=False, default=None, soft=None, extra_items=(), **kw):
    """A bpy property for schema option `name`. The Scene's has the schema's limits as hard
    limits. The operator's (operator=True) has them as soft limits only, so that a script's
    out-of-range value reaches execute() and is refused with the schema's message instead of
    being clamped silently. default: for options whose schema default is unset (None);
    soft: (soft_min, soft_max) within the limits for the UI's slider; extra_items: enum
    items before the schema's choices."""
    spec = option_spec(name)
    value = spec.default if default is None else default
    common = dict(name=spec.label, description=_description(spec), **kw)
    if spec.type in ("int", "float"):
        low, high = hard_limits(spec)
        soft_low, soft_high = soft if soft is not None else (low, high)
        soft_low, soft_high = max(soft_low, low), min(soft_high, high)
        if spec.type == "int":
            limits = dict(soft_min=int(soft_low), soft_max=int(soft_high))
            if not operator:
                limits.update(min=int(low), max=int(high))
            return IntProperty(default=int(value), subtype="NONE", **limits, **common)
        limits = dict(soft_min=soft_low, soft_max=soft_high)
        if not operator:
            limits.update(min=low, max=high)
        unit = {"world units": dict(subtype="DISTANCE", unit="LENGTH")}.get(spec.unit, dict(subtype="NONE"))
        return FloatProperty(default=float(value), precision=4, **limits, **unit, **common)
    if spec.type == "choice":
        labels = CHOICE_LABELS.get(name, {})
        items = [(c, *labels.get(c, (c.title(), c))) for c in list(extra_items) + list(spec.choices)]
        return EnumProperty(items=items, default=value, **common)
    if spec.type == "bool":
        return BoolProperty(default=bool(value), **common)
    if spec.type == "str":
        return StringProperty(default=value, **common)
    raise TypeError(f"option {name} ({spec.type}) has no Blender property")


# The voxelize settings an artist sets per scene; the operator declares the same names.
def scene_and_operator_properties(operator=False):
    skip = {"options": {"SKIP_SAVE"}} if operator else {}
    return {
        "size_mode": EnumProperty(name="Size", description="Set the grid by resolution or by voxel size",
                                  items=SIZE_ITEMS, default="RESOLUTION", **skip),
        "resolution": schema_property("resolution", operator, soft=(8, 2048), **skip),
        "voxel_size": schema_property("voxel_size", operator, default=0.05, soft=(1e-4, 10.0), **skip),
        "method": schema_property("method", operator, default=backend.AUTO_METHOD,
                                  extra_items=(backend.AUTO_METHOD,), **skip),
        "mode": schema_property("mode", operator, **skip),
        # Like Mesh to Volume's Fill Volume: on, the run is solid whatever the mode says.
        "fill_interior": BoolProperty(name="Fill Interior", description="Fill the inside of the mesh too "
                                      "(solid mode); holes and flipped faces are bridged by the winding number",
                                      default=True, **skip),
        "inside": schema_property("inside", operator, **skip),
        "tess_gamma": schema_property("tess_gamma", operator, soft=(0.5, 4.0), **skip),
        "hybrid_cutoff": schema_property("hybrid_cutoff", operator, soft=(-1.0, 4096.0), **skip),
        "padding": schema_property("padding", operator, soft=(0, 64), **skip),
        "separate": BoolProperty(name="One Volume per Object", description="Make one volume for every "
                                 "selected object instead of one for the whole selection", default=False, **skip),
        "output_dir": StringProperty(name="Output Folder", description="Where the .vdb files go; empty: a "
                                     "hyvox_cache folder next to the .blend, or the temp folder if unsaved",
                                     default="", subtype="DIR_PATH", **skip),
        "use_frame_range": BoolProperty(name="Frame Range", description="Voxelize every frame of a range "
                                        "into a .vdb sequence", default=False, **skip),
        "frame_start": IntProperty(name="Start", description="First frame of the sequence", default=1,
                                   min=0, subtype="TIME", **skip),
        "frame_end": IntProperty(name="End", description="Last frame of the sequence", default=250,
                                 min=0, subtype="TIME", **skip),
    }


# The settings that stand for schema options, by the property's (= the option's) name.
SCENE_OPTIONS = ("resolution", "voxel_size", "mode", "inside", "tess_gamma", "hybrid_cutoff", "padding")
PREFERENCE_OPTIONS = ("threads", "memory_budget_mib")


class HyvoxSceneSettings(bpy.types.PropertyGroup):
    __annotations__ = scene_and_operator_properties()


def _preferences_properties():
    device = option_spec("gl_device")
    return {
        "gl_device": EnumProperty(name=device.label, description=_description(device),
                                  items=[("AUTO", "Automatic", "A hardware GPU if there is one, else software"),
                                         ("SOFTWARE", "Software", "Mesa's llvmpipe (slow; always works)"),
                                         ("INDEX", "By Index", "The EGL device with the index below")],
                                  default="AUTO"),
        "gl_device_index": IntProperty(name="Device Index", description="Index of the EGL device to use",
                                       default=0, min=0, max=63, subtype="NONE"),
        "memory_budget_mib": schema_property("memory_budget_mib", soft=(16, 65536)),
        "threads": schema_property("threads", soft=(0, 64)),
        "alignment_fix": EnumProperty(name="Half-Voxel Fix", description="Move volumes by half a voxel to "
                                      "match how this Blender draws OpenVDB voxel centres",
                                      items=[("AUTO", "Automatic", "By Blender version"),
                                             ("ON", "On", "Always correct"),
                                             ("OFF", "Off", "Never correct")], default="AUTO"),
    }


ADDON_NAME = __package__.rpartition(".")[0]


class HyvoxPreferences(bpy.types.AddonPreferences):
    bl_idname = ADDON_NAME
    __annotations__ = _preferences_properties()

    def draw(self, context):
        layout = self.layout
        row = layout.row()
        row.prop(self, "gl_device")
        sub = row.row()
        sub.enabled = self.gl_device == "INDEX"
        sub.prop(self, "gl_device_index")
        layout.prop(self, "memory_budget_mib")
        layout.prop(self, "threads")
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

