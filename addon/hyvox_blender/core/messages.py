# SPDX-License-Identifier: GPL-3.0-or-later
"""The module's messages in the add-on's words: a setting named where the artist finds it
(the add-on's preferences), not by the module's option name."""

import re

# Where the add-on shows the module's options that are not in the panel (blender/ui/properties.py:
# the preference's name is the schema's label).
PREFERENCES = {"memory_budget_mib": "Preferences \u25b8 Memory Budget"}

_BUDGET = re.compile(r"(memory budget of \d+ MiB)")


def in_addon_words(text: str) -> str:
    """'... more than the memory budget of 16 MiB; raise the budget (memory_budget_mib) ...' ->
    '... more than the memory budget of 16 MiB (Preferences ▸ Memory Budget); raise the budget ...'."""
    where = PREFERENCES["memory_budget_mib"]
    if where in text:
        return text
    text = text.replace(" (memory_budget_mib)", "")
    return _BUDGET.sub(lambda m: f"{m.group(1)} ({where})", text, count=1)
