"""Which hidden set a grading ran: the instructor's data file and the variants the seed drew from it.

Recorded in every batch result (``batch.hidden_set``) and in ``batch.json`` so that an instructor can
tell, months later, whether two gradings ran the same hidden variants: the seed alone does not say it
(the instructor may have edited ``instructor_tools/hidden/weekN.json`` in between), and two seeds may
draw the same variants. The draws are the checks' own (``hidden_picks`` in grader/checks/weekN.py),
never re-implemented here.
"""

from __future__ import annotations

import hashlib
import importlib
import json
from typing import Any

from grader.hidden import WEEKS_WITH_DATA, hidden_dir

# week -> the modes whose variants grader/checks/weekN.py draws separately (None: one draw)
_MODES: dict[int, tuple[str | None, ...]] = {4: (None,), 5: ("blending", "switching"), 6: (None,), 7: (None,)}


def hidden_set_identity(week: int, seed: int) -> dict[str, Any]:
    """``{"seed", "checks", "file", "file_sha256", "variants", "digest"}`` for grading ``week`` with its
    hidden checks and ``seed``.

    ``digest`` (16 hex) covers the hidden check ids, the data file's bytes and the drawn variants; for
    weeks whose hidden checks read no data file (1-3: their hidden cases come from the seed alone) it
    covers the check ids and the seed. ``file_sha256`` is "" when the week has no file here (a student
    install), which official grading never uses.
    """
    from grader.checks import checks_for_week

    checks = sorted(c.id for c in checks_for_week(week) if c.visibility != "visible")
    identity: dict[str, Any] = {"seed": seed, "checks": checks, "file": "", "file_sha256": "",
                                "variants": []}
    if week in WEEKS_WITH_DATA:
        path = hidden_dir() / f"week{int(week)}.json"
        identity["file"] = path.name
        try:
            raw = path.read_bytes()
        except OSError:
            raw = None
        if raw is not None:
            identity["file_sha256"] = hashlib.sha256(raw).hexdigest()
            data = json.loads(raw.decode("utf-8"))
            module = importlib.import_module(f"grader.checks.week{int(week)}")
            for mode in _MODES[week]:
                picks = module.hidden_picks(data, seed, *([mode] if mode else []))
                identity["variants"] += [{"mode": mode, **p} if mode else p for p in picks]
        material: Any = [checks, identity["file_sha256"], identity["variants"]]
    else:
        material = [checks, seed]
    encoded = json.dumps(material, sort_keys=True, separators=(",", ":")).encode()
    identity["digest"] = hashlib.sha256(encoded).hexdigest()[:16]
    return identity
