"""Settings a student's QBSupervisor sets under a misspelt name (`self.fw_directon = "right"`), for
`simiam run` to warn about before the run.

The framework reads the settings by name (simiam.control.supervisor: v, goal, d_stop, theta_d, d_at_obs,
d_unsafe, d_fw, fw_direction; week 5's is_blending in the student's own execute), so a misspelt one is set,
never read, and the run silently uses the default. Students add attributes of their own too, so this is a
warning, and only for a name that is close to a setting's, is assigned on `self` in qb_supervisor.py and
is never read there (a name the student's code reads is theirs, whatever it looks like).
"""

from __future__ import annotations

import ast

from simiam.course.week import EXTRA_SETTINGS, NAMED_SETTINGS
from simiam.names import closest_first, likely_meant

# the settings a student sets as attributes (state, estimate and gains are given to a run, not set)
STUDENT_SETTINGS = tuple(n for n in NAMED_SETTINGS + EXTRA_SETTINGS
                         if n not in ("state", "estimate", "gains"))
CLOSE = 0.8  # difflib similarity from which an unread name is taken for a misspelt setting


def misspelt_settings(source: str, file: str = "qb_supervisor.py") -> list[str]:
    """One warning per attribute `self.X` that `source` assigns and never reads, X not a setting but close
    to one: "qb_supervisor.py, line 57: self.fw_directon is set but never read; did you mean
    self.fw_direction? (the settings the simulator reads, closest first: fw_direction, ...)". Nothing for
    source that does not parse (the loader says so)."""
    try:
        tree = ast.parse(source)
    except (SyntaxError, ValueError):
        return []
    assigned: dict[str, int] = {}
    read: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "self":
            if isinstance(node.ctx, ast.Store):  # the first line that sets it (ast.walk is not in line order)
                assigned[node.attr] = min(assigned.get(node.attr, node.lineno), node.lineno)
            else:
                read.add(node.attr)
    warnings = []
    for name, line in sorted(assigned.items(), key=lambda item: item[1]):
        if name in STUDENT_SETTINGS or name in read:
            continue
        meant = likely_meant(name, STUDENT_SETTINGS, cutoff=CLOSE)
        if meant is not None:
            known = ", ".join(closest_first(name, STUDENT_SETTINGS))
            warnings.append(f"{file}, line {line}: self.{name} is set but never read; did you mean "
                            f"self.{meant}? (the settings the simulator reads, closest first: {known})")
    return warnings
