# SPDX-License-Identifier: GPL-3.0-or-later
"""Live: volumes that update by themselves when their sources change. driver.py: the session's
state, the handlers and timer that drive the runs (the design: core/live_scheduler.py);
volumes.py: a live volume's settings, sources, export and swap; dependencies.py: the sources
kept in the dependency graph for renders; panel.py: the Live sub-panel."""
