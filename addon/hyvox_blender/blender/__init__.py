# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's Blender side: properties, operator, panel, mesh export, volume import."""
