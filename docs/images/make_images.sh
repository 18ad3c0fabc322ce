#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Makes the documentation's pictures in docs/images/ from a build: the demo's Cycles renders
# (demo/run_demo.py, as `bash scripts/run_demo.sh` makes them) and screenshots of the add-on's
# panel in a real Blender window under Xvfb (tests/blender/interactive_panel.py), cropped to
# the sidebar and made small enough to commit.
#   bash docs/images/make_images.sh [BUILD [PART...]]   (default build/, both parts: demo, the
#                                                       renders, and panel, the screenshots;
#                                                       needs xvfb-run, python3-pil)
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=${1:-build}
parts=("${@:2}")
[ ${#parts[@]} -gt 0 ] || parts=(demo panel)
wanted() { [[ " ${parts[*]} " == *" $1 "* ]]; }
[ -d "$BUILD/addon/hyvox_blender" ] || { echo "make_images.sh: build the project first ($BUILD/addon)" >&2; exit 2; }
export PATH=/usr/bin:/bin:$PATH
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

if wanted demo; then
  blender -b --factory-startup --python demo/run_demo.py -- --build "$BUILD" --output "$work/demo" \
    >"$work/demo.log" 2>&1 ||
    { tail -20 "$work/demo.log"; exit 1; }
fi
if wanted panel; then
  mkdir -p "$work/shots"
  xvfb-run -a -s "-screen 0 1400x1300x24" blender --factory-startup --enable-event-simulate -p 0 0 1400 1300 \
    --python-exit-code 1 --python tests/blender/interactive_panel.py -- "$BUILD" "$work/shots" >"$work/panel.log" 2>&1 ||
    { tail -20 "$work/panel.log"; exit 1; }
fi

/usr/bin/python3 - "$work" docs/images <<'PY'
import json
import pathlib
import sys

from PIL import Image

work, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])


def save(image, name, width):
    image = image.convert("RGB")
    if image.width > width:
        image = image.resize((width, round(image.height * width / image.width)), Image.LANCZOS)
    path = out / name
    if name.endswith(".jpg"):
        image.save(path, quality=85, optimize=True, progressive=True)
    else:
        image.save(path, optimize=True)
    print(f"{path}: {image.width}x{image.height}, {path.stat().st_size // 1024} KiB")


def sidebar(name):
    """The screenshot cropped to the sidebar's panels: its rectangle (pixels from the bottom
    left) less the tab strip on the right, down to where the panels' backgrounds end."""
    shot = Image.open(work / "shots" / name).convert("RGB")
    r = json.loads((work / "shots" / (name + ".json")).read_text())
    top = max(shot.height - (r["y"] + r["height"]), 0)
    panels = shot.crop((r["x"], top, r["x"] + r["width"] - 24, shot.height - r["y"]))
    backgrounds = {panels.getpixel((12, y)) for y in range(0, 60)}  # panel headers and bodies
    end = next((y for y in range(panels.height) if panels.getpixel((12, y)) not in backgrounds), panels.height)
    return panels.crop((0, 0, panels.width, min(end + 4, panels.height)))


if (work / "demo").is_dir():
    save(Image.open(work / "demo" / "render.png"), "demo_render.jpg", 800)
    save(Image.open(work / "demo" / "render_colour.png"), "demo_render_colour.jpg", 640)
    save(Image.open(work / "demo" / "render_colour_sponza.png"), "demo_render_colour_sponza.jpg", 640)
if (work / "shots").is_dir():
    save(sidebar("panel_before_run.png"), "panel.png", 400)
    save(sidebar("panel_after_run.png"), "panel_after_run.png", 400)
PY
