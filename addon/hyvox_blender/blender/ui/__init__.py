# SPDX-License-Identifier: GPL-3.0-or-later
"""What the artist sets and sees: properties.py (Scene settings and preferences, from the
options schema), panels.py (the sidebar), legacy_settings.py (settings of earlier versions
read as meant)."""
