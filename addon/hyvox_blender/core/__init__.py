# SPDX-License-Identifier: GPL-3.0-or-later
"""The add-on's bpy-free layer: settings, calling the hyvox module, file naming,
alignment math and summaries. Nothing here imports bpy, so pytest covers it with the
system Python and pipelines can reuse it outside Blender."""
