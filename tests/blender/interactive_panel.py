# SPDX-License-Identifier: GPL-3.0-or-later
"""The sidebar panel in a real window: no label, value or summary line is wider than the
room the sidebar gives it at its default width, and no label is drawn twice in a panel
(in either size mode).

    xvfb-run -a blender --factory-startup --enable-event-simulate \\
        --python tests/blender/interactive_panel.py -- BUILD_DIR [SCREENSHOT_DIR]

Blender's Python API does not report the widths of the drawn widgets, so each panel's
draw() runs against a recording layout that notes what goes where (label column, value
column, full width) the way Blender's property-split layout places it, and the width of
every text, measured with blf in the UI font at the UI scale, is compared with the room of
its column in the sidebar's real region width (factory default). With SCREENSHOT_DIR, it
also saves screenshots of the window before and after a run (sub-panels open).
Exits 0 on success, 1 on failure."""

import json
import os
import sys
import tempfile

import blf
import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import helpers  # noqa: E402

SPLIT = 0.4  # Blender's property-split label share (UI_ITEM_PROP_SEP_DIVIDE)


def fail(message):
    print("PANEL TEST FAILED:", message, flush=True)
    os._exit(1)


class Recorder:
    """Enough of bpy.types.UILayout for the add-on's draw() methods: records (where, text)
    with where in {'label', 'value', 'full', 'share:N'}."""

    def __init__(self, out, split=False, heading=""):
        self.out, self.use_property_split, self.heading = out, split, heading
        self.heading_drawn = False
        self.use_property_decorate = self.enabled = self.active = True
        self.alignment = "EXPAND"
        self._row_items = None

    def _child(self, heading=""):
        return Recorder(self.out, self.use_property_split, heading)

    def column(self, align=False, heading=""):
        return self._child(heading)

    def row(self, align=False, heading=""):
        child = self._child(heading)
        child._row_items = []
        return child

    box = split = column

    def label(self, text="", icon="NONE"):
        self.out.append(("full", text, icon != "NONE"))

    def operator(self, idname, text=None, icon="NONE", **_):
        if text is None:
            module, name = idname.split(".")
            text = getattr(getattr(bpy.ops, module), name).get_rna_type().name
        self.out.append(("full", text, icon != "NONE"))

    def prop(self, data, name, text=None, expand=False, **_):
        rna = data.bl_rna.properties[name]
        label = rna.name if text is None else text
        if rna.type == "ENUM" and expand:  # one button per item, sharing a column
            items = list(rna.enum_items)
            if self.use_property_split:
                self.out.append(("label", label, False))
            share = "value_share" if self.use_property_split else "share"
            count = len(items) if self._row_items is not None else 1  # a column stacks them
            for item in items:
                self.out.append((f"{share}:{count}", item.name, False))
            return
        if rna.type == "BOOLEAN":
            if self.use_property_split:
                # The check box's text goes right of it in the value column; a column's
                # heading, if any, left of its first check box.
                if self.heading and not self.heading_drawn:
                    self.out.append(("label", self.heading, False))
                    self.heading_drawn = True
                self.out.append(("value_check", label, False))
            else:
                self.out.append(("full_check", label, False))
            return
        if self.use_property_split:
            self.out.append(("label", label, False))
            if rna.type == "ENUM":
                value = getattr(data, name)
                shown = next(i.name for i in rna.enum_items if i.identifier == value)
                self.out.append(("value_menu", shown, rna.enum_items[value].icon != "NONE"))
        else:
            self.out.append(("full", label, False))


def room(where, content, unit):
    """Pixels a text may take in a column of a panel whose content is `content` wide."""
    value = content * (1 - SPLIT)
    limit = {
        "label": content * SPLIT - unit * 0.5,
        "value_menu": value - unit * 1.5,  # the drop-down arrow and padding
        "value_check": value - unit * 1.5,  # the check box before the text
        "full": content - unit,
        "full_check": content - unit * 1.5,
    }.get(where)
    if limit is not None:
        return limit
    kind, count = where.split(":")
    return (value if kind == "value_share" else content - unit) / int(count) - unit * 0.5


def panels():
    from hyvox_blender.blender.live import panel as live_ui
    from hyvox_blender.blender.ui import panels as ui

    return ui.CLASSES + (live_ui.VIEW3D_PT_hyvox_live,)


def check_widths(context, region):
    scale = context.preferences.system.ui_scale
    unit = 20 * scale
    points = context.preferences.ui_styles[0].widget.points
    blf.size(0, points * scale, 72)
    # The region's width less the category tabs and the panel's margins on both sides.
    content = region.width - unit - unit
    print(f"sidebar region {region.width} px, panel content {content:.0f} px, ui scale {scale:.3f}", flush=True)
    too_wide = []
    settings = context.scene.hyvox
    for panel, size_mode in [(panel, "RESOLUTION") for panel in panels()] + [(panels()[0], "VOXEL_SIZE")]:
        settings.size_mode = size_mode
        out = []
        recorder = Recorder(out)

        def layout_split(_self, layout=recorder):
            layout.use_property_split = True
            return layout

        fake = type("FakePanel", (), {"layout": recorder, "layout_split": layout_split})()
        if hasattr(panel, "draw_header"):
            panel.draw_header(fake, context)
        panel.draw(fake, context)
        labels = [text for where, text, _ in out if where == "label"]
        twice = sorted({text for text in labels if labels.count(text) > 1})
        if twice:
            too_wide.append(f"{panel.bl_label} ({size_mode}): the label {twice} twice")
        for where, text, icon in out:
            width = blf.dimensions(0, text)[0] + (unit if icon else 0)
            limit = room(where, content, unit)
            print(f"  {panel.bl_label:10s} {where:12s} {width:6.1f} / {limit:6.1f}  {text!r}", flush=True)
            if width > limit:
                too_wide.append(f"{panel.bl_label}: {text!r} ({width:.0f} px in {limit:.0f} px)")
    return too_wide


def sidebar():
    window = bpy.context.window_manager.windows[0]
    for area in window.screen.areas:
        if area.type == "VIEW_3D":
            area.spaces[0].show_region_ui = True
            return window, area, next(r for r in area.regions if r.type == "UI")
    fail("no 3D View")


def screenshot(directory, name):
    window, _, region = sidebar()
    with bpy.context.temp_override(window=window, screen=window.screen):
        bpy.ops.screen.screenshot(filepath=os.path.join(directory, name))
    # Where the sidebar is in it (window pixels from the bottom left), for the documentation's
    # crop (docs/images/make_images.sh).
    with open(os.path.join(directory, name + ".json"), "w") as f:
        json.dump({"x": region.x, "y": region.y, "width": region.width, "height": region.height}, f)


state = {"step": 0}


def step():
    argv = sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else []
    shots = argv[1] if len(argv) > 1 else None
    s = state["step"]
    state["step"] += 1
    window, area, region = sidebar()
    if s == 0:
        helpers.close_splash()
        helpers.clear_scene()
        bunny = helpers.bunny()
        helpers.select_only(bunny)
        area.tag_redraw()
        return 0.5
    if s == 1 and shots and not state.get("transform_closed"):
        # For the screenshots, close the tab's Transform panel above ours with a click on its
        # header (the sidebar's top row), then come back to this step.
        x, y = region.x + region.width // 2, region.y + region.height - 12
        window.event_simulate("LEFTMOUSE", "PRESS", x=x, y=y)
        window.event_simulate("LEFTMOUSE", "RELEASE", x=x, y=y)
        state["transform_closed"] = True
        state["step"] = 1
        area.tag_redraw()
        return 0.5
    if s == 1:
        if shots:
            screenshot(shots, "panel_before_run.png")
        # The size from the panel's own setting, so the picture after the run shows the
        # setting that made its result.
        bpy.context.scene.hyvox.resolution = 64
        with bpy.context.temp_override(window=window, area=area, region=region):
            result = bpy.ops.object.hyvox_voxelize(method="cpu", output_dir=OUT)
        if result != {"FINISHED"}:
            fail(f"the run returned {result}")
        # After a run the result is selected, active and visible.
        active = bpy.context.view_layer.objects.active
        if active is None or active.name != "Bunny_voxels" or not active.select_get() or not active.visible_get():
            fail(f"after the run the active object is {active and active.name}, not the visible, selected volume")
        area.tag_redraw()
        return 0.5
    if shots:
        screenshot(shots, "panel_after_run.png")
    too_wide = check_widths(bpy.context, region)
    if too_wide:
        fail("cut in the sidebar: " + "; ".join(too_wide))
    print("PANEL TEST PASSED", flush=True)
    os._exit(0)


def prepare(build):
    sys.path.insert(0, os.path.join(build, "addon"))
    # Show the panel in the sidebar's first tab and its sub-panels open, for the screenshots
    # (the widths do not depend on either).
    for panel in panels():
        panel.bl_category = "Item"
        panel.bl_options = set(getattr(panel, "bl_options", set())) - {"DEFAULT_CLOSED"}


OUT = tempfile.mkdtemp(prefix="hyvox-panel-")
helpers.run_in_window(step, fail, seconds=120, prepare=prepare)
