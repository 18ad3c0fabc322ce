# SPDX-License-Identifier: GPL-3.0-or-later
"""From Blender to the pipeline: sources.py picks the sources and exports their evaluated
meshes (triangles.py reads the triangles, colour.py the colours the materials show);
frames.py exports a frame of a run, with a render evaluation where it can differ
(render_depsgraph.py, render_equivalence.py)."""
