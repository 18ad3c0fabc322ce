# SPDX-License-Identifier: GPL-3.0-or-later
"""The results in Blender: importer.py makes or updates the Volume objects, material.py their
material, eevee_bounds.py the modifier that keeps EEVEE's bounds, blocks.py the Blocks mesh;
node_groups.py builds the node groups these use."""
