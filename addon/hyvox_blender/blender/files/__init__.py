# SPDX-License-Identifier: GPL-3.0-or-later
"""The voxel files: history.py (what undo may reach), handlers.py (moved next to a saved
.blend, session folders), clean.py (Clean Unused Files)."""
