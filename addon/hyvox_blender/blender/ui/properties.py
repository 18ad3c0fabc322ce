# SPDX-License-Identifier: GPL-3.0-or-later
"""The Scene's voxelize settings (scene.hyvox), the add-on preferences, and the builder both
they and the operator take their properties from.

Every property that stands for a hyvox option is made from the native options schema
(hyvox.OPTIONS): its name, description, default, limits and choices are the schema's, so
the add-on cannot drift from the CLI and the Python module. Blender's limits are inclusive:
an exclusive minimum (voxel size > 0) becomes min + EXCLUSIVE_STEP."""

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

from ...core import backend, panel_rules

FLOAT_LIMIT = 3.4028234e38  # Blender float properties are float32
INT_LIMIT = 2**31 - 1  # ... and int properties int32
EXCLUSIVE_STEP = 1e-6

# How the choices of the schema's enums read in the UI; a choice missing here still
# appears, under its own name.
CHOICE_LABELS = {
    "method": {
        backend.AUTO_METHOD: ("Auto", "Hybrid GL voxelizer when a GPU runs OpenGL 4.5 here, else CPU"),
        "hybrid": ("Hybrid (GPU)", "Triangle- and fragment-parallel passes split by triangle size (exact)"),
        "triangle": ("Triangle (GPU)", "One GPU thread per triangle (exact; best for many small triangles)"),
        "fragment": ("Fragment (GPU)", "Rasterized, one fragment per voxel column (exact; best for large triangles)"),
        "tessellation": (
            "Tessellation (GPU)",
            "Adaptive point tessellation (approximate, fast; may miss a few voxels)",
        ),
        "cpu": ("CPU", "Exact multi-threaded CPU voxelizer (no GPU needed)"),
        "reference": ("Reference", "Brute-force exact oracle (slow; for checking results)"),
    },
    "mode": {
        "conservative": ("Surface", "Every voxel the surface touches (conservative, 26-separating)"),
        "thin": (
            "Thin Surface",
            "Fewer voxels: the thinnest surface that still keeps the inside and the outside apart (thin, 6-separating)",
        ),
        "solid": ("Solid", "The surface and everything inside it, like Mesh to Volume's Fill Volume (solid)"),
    },
    "inside": {
        "auto": (
            "Auto",
            "Right for closed meshes and for meshes with holes or flipped faces (the winding "
            "number: exact by rays when closed, fast winding numbers when open)",
        ),
        "parity": ("Parity", "Inside where a ray crosses the surface an odd number of times: closed meshes only"),
        "winding": (
            "Winding Number",
            "Bridges holes and flipped faces (inside where the winding number is at least 0.5)",
        ),
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


# Tooltips start in plain words; the schema's help (with the term) follows.
PLAIN_WORDS = {
    "resolution": "How many voxels fit along the longest side of the objects",
    "voxel_size": "How big one voxel is",
    "mode": "What the voxels hold: the surface, or the surface and everything inside it",
    "inside": "How Solid tells the inside from the outside",
    "tess_gamma": "How many points the tessellation method puts on each triangle: more misses fewer voxels "
    "and takes longer",
    "hybrid_cutoff": "The hybrid method rasterizes the triangles larger than this and gives each smaller one a "
    "thread of its own; -1 picks the size by itself",
    "padding": "Empty voxels around the objects",
    "memory_budget_mib": "How much memory a run may take for its voxels; a grid that needs more is refused",
    "threads": "How many CPU threads a run uses; 0 uses every core",
}


def method_items():
    """Auto first, then the schema's methods. The list is fixed: which GL device the GL methods
    would run on here is asked only when the panel first draws (its note under Method,
    ui.py), so enabling the add-on loads neither the GL plugin nor a device list."""
    labels = CHOICE_LABELS["method"]
    items = []
    for number, choice in enumerate([backend.AUTO_METHOD] + list(option_spec("method").choices)):
        name, description = labels.get(choice, (choice.title(), choice))
        if choice in panel_rules.GL_METHODS:
            name = name.replace(" (GPU)", "")
            description += ". Needs OpenGL 4.5; the note under Method says where it runs here"
        items.append((choice, name, description, "NONE", number))
    return items


def schema_property(name, operator=False, default=None, soft=None, extra_items=(), **kw):
    """A bpy property for schema option `name`. The Scene's has the schema's limits as hard
    limits. The operator's (operator=True) has them as soft limits only, so that a script's
    out-of-range value reaches execute() and is refused with the schema's message instead of
    being clamped silently. default: for options whose schema default is unset (None);
    soft: (soft_min, soft_max) within the limits for the UI's slider; extra_items: enum
    items before the schema's choices."""
    spec = option_spec(name)
    value = spec.default if default is None else default
    description = _description(spec)
    if name in PLAIN_WORDS:
        description = f"{PLAIN_WORDS[name]} ({description[:1].lower() + description[1:]})"
    common = dict(name=spec.label, description=description, **kw)
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


def _scene_range_on_first_use(settings, context):
    """Turning the frame range on starts from the scene's range, unless one was set."""
    if settings.use_frame_range and not (
        settings.is_property_set("frame_start") or settings.is_property_set("frame_end")
    ):
        settings.frame_start, settings.frame_end = context.scene.frame_start, context.scene.frame_end


# The voxelize settings an artist sets per scene; the operator declares the same names.
def scene_and_operator_properties(operator=False):
    skip = {"options": {"SKIP_SAVE"}} if operator else {}
    return {
        "size_mode": EnumProperty(
            name="Size",
            description="Set the grid by a number of voxels (Resolution) or by the size of one voxel (Voxel Size)",
            items=SIZE_ITEMS,
            default="RESOLUTION",
            **skip,
        ),
        "resolution": schema_property("resolution", operator, soft=(8, 2048), **skip),
        "voxel_size": schema_property("voxel_size", operator, default=0.05, soft=(1e-4, 10.0), **skip),
        "method": EnumProperty(
            name="Method",
            items=method_items(),
            default=backend.AUTO_METHOD,
            description="Which voxelizer runs ("
            + _description(option_spec("method"))[:1].lower()
            + _description(option_spec("method"))[1:]
            + ")",
            **skip,
        ),
        # Solid by default, like Mesh to Volume's Fill Volume (legacy_settings.py maps the
        # Fill Interior switch of earlier versions onto it).
        "mode": schema_property("mode", operator, default="solid", **skip),
        "inside": schema_property("inside", operator, **skip),
        "tess_gamma": schema_property("tess_gamma", operator, soft=(0.5, 4.0), **skip),
        "hybrid_cutoff": schema_property("hybrid_cutoff", operator, soft=(-1.0, 4096.0), **skip),
        "padding": schema_property("padding", operator, soft=(0, 64), **skip),
        "separate": BoolProperty(
            name="One Volume per Object",
            description="Make one volume for every selected object instead of one for the whole selection",
            default=False,
            **skip,
        ),
        "output_dir": StringProperty(
            name="Output Folder",
            description="Where the .vdb files go; empty: a "
            "hyvox_cache folder next to the .blend, or the temp folder if unsaved",
            default="",
            subtype="DIR_PATH",
            **skip,
        ),
        "output": EnumProperty(
            name="Output",
            description="What the voxels become in the scene",
            items=[
                ("VOLUME", "Volume", "An OpenVDB volume object (renders as fog or smoke)"),
                ("BLOCKS", "Blocks", "A mesh of one cube per voxel with only the outer faces (one frame)"),
            ],
            default="VOLUME",
            **skip,
        ),
        "color": BoolProperty(
            name="Color",
            description="Give the voxels the color the objects' materials show "
            "(the render color attribute, else the Base Color's image or value): the volume's "
            "material, Blocks and .vox files show it; objects without a material add none. "
            "Solid: the inside takes the color of the surface around it",
            default=True,
            **skip,
        ),
        "signed_distance": BoolProperty(
            name="SDF Grid",
            description="Also store the signed distance to "
            "the surface near it, negative inside, as a grid named sdf (a level set) for "
            "Blender's SDF grid nodes and a smooth Grid to Mesh. Meshes with holes keep "
            "their inside (the winding number decides it)",
            default=False,
            **skip,
        ),
        "export_vox": BoolProperty(
            name="MagicaVoxel File",
            description="Also write the voxels as a MagicaVoxel "
            ".vox file next to the .vdb (split into models of at most 256 per side; at "
            "most 255 colors)",
            default=False,
            **skip,
        ),
        "parent_to_source": BoolProperty(
            name="Parent to Source",
            description="Parent the volume to the "
            "object it was made from, so moving that object moves it (not for frame "
            "ranges: their voxels already follow the animation)",
            default=True,
            **skip,
        ),
        "evaluation": EnumProperty(
            name="Modifiers",
            description="Which settings modifiers and Geometry "
            "Nodes are evaluated at (Subdivision levels, Simplify, Is Viewport)",
            items=[
                ("RENDER", "Render", "As the render shows the scene (the final result)"),
                ("VIEWPORT", "Viewport", "As the viewport shows it (faster to evaluate)"),
            ],
            default="RENDER",
            **skip,
        ),
        "hide_source": BoolProperty(
            name="Hide Source",
            description="Hide the objects a run voxelized, so the result is seen on its own",
            default=False,
            **skip,
        ),
        "live": BoolProperty(
            name="Live",
            description="Keep the new volumes up to date by themselves: they follow "
            "edits, modifiers, transforms, materials and the animation (no frame range needed)",
            default=False,
            **skip,
        ),
        "use_frame_range": BoolProperty(
            name="Frame Range",
            description="Voxelize every frame of a range into a .vdb sequence (the scene's range unless you set one)",
            default=False,
            update=None if operator else _scene_range_on_first_use,
            **skip,
        ),
        "frame_start": IntProperty(
            name="Start", description="First frame of the sequence", default=1, min=0, subtype="TIME", **skip
        ),
        "frame_end": IntProperty(
            name="End", description="Last frame of the sequence", default=250, min=0, subtype="TIME", **skip
        ),
    }


# The settings that stand for schema options, by the property's (= the option's) name.
SCENE_OPTIONS = ("resolution", "voxel_size", "mode", "inside", "tess_gamma", "hybrid_cutoff", "padding")
PREFERENCE_OPTIONS = ("threads", "memory_budget_mib")


class HyvoxSceneSettings(bpy.types.PropertyGroup):
    __annotations__ = scene_and_operator_properties()


def _preferences_properties():
    device = option_spec("gl_device")
    return {
        "gl_device": EnumProperty(
            name=device.label,
            description=_description(device),
            items=[
                ("AUTO", "Automatic", "A hardware GPU if there is one, else software"),
                ("SOFTWARE", "Software", "Mesa's llvmpipe (slow; always works)"),
                ("INDEX", "By Index", "The EGL device with the index below"),
            ],
            default="AUTO",
        ),
        "gl_device_index": IntProperty(
            name="Device Index", description="Index of the EGL device to use", default=0, min=0, max=63, subtype="NONE"
        ),
        "memory_budget_mib": schema_property("memory_budget_mib", soft=(0, 65536)),
        "threads": schema_property("threads", soft=(0, 64)),
        "alignment_fix": EnumProperty(
            name="Half-Voxel Fix",
            description="Move volumes by half a voxel to match how this Blender draws OpenVDB voxel centres",
            items=[
                ("AUTO", "Automatic", "By Blender version"),
                ("ON", "On", "Always correct"),
                ("OFF", "Off", "Never correct"),
            ],
            default="AUTO",
        ),
    }


# The add-on's package (hyvox_blender, or bl_ext.<repository>.hyvox_blender as an extension):
# this module's, less blender.ui.
ADDON_NAME = __package__.rsplit(".", 2)[0]


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
