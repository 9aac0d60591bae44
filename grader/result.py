"""The result model: one check's outcome, one submission's result (the contract's JSON), the check-set hash.

Everything here is plain data. A result dict is what `grade_submission` returns, what the batch runner
stores and what the HTML report renders; the traces of scenario checks travel next to it, never inside it.
"""

from __future__ import annotations

import hashlib
import importlib
import inspect
import json
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

STATUSES = ("passed", "failed", "error", "timeout")


@dataclass
class CheckResult:
    """One check's outcome: points earned of max_points, a status, a message a student can act on."""

    id: str
    name: str
    kind: str
    visibility: str
    max_points: float
    points: float = 0.0
    status: str = "failed"
    message: str = ""
    details: dict[str, Any] = field(default_factory=dict)
    plots: tuple[str, ...] = ()  # what the report draws for each run of a scenario check (Check.plots)
    # what the student's code printed while a hidden check ran: it may show the hidden goals, so it goes
    # with this check's result and visibility, never into the result's top-level student_output
    printed: str = ""

    def to_json(self) -> dict[str, Any]:
        """The contract's per-check record (plus `visibility`, `plots` for a scenario check, and `printed`
        for a hidden check during which the student's code printed something)."""
        record: dict[str, Any] = {
            "id": self.id,
            "name": self.name,
            "kind": self.kind,
            "visibility": self.visibility,
            "points": round(self.points, 6),
            "max_points": self.max_points,
            "status": self.status,
            "message": self.message,
            "details": self.details,
        }
        if self.plots:
            record["plots"] = list(self.plots)
        if self.printed:
            record["printed"] = self.printed
        return record


def package_version() -> str:
    """simiam's version, the one its distribution is built with (`simiam.__version__`, which pyproject.toml
    reads): the version of the code that runs, read without importlib.metadata's ~30-50 ms of imports."""
    from simiam import __version__

    return __version__


# The code that decides a score besides the checks' own functions: a change here changes the hash too.
_EXPECTED = Path(__file__).resolve().parent / "checks" / "expected"
# The probes count with the registry: every module a registered probe is defined in (grader.inside.probes).
_SCORING_MODULES = ("grader.reference", "grader.properties", "grader.scenarios", "grader.inside.probes",
                    "grader.inside.probing", "grader.checks.answers", "grader.hidden", "grader.hidden.draw",
                    "grader.practice")  # grader.practice: which variants a hidden check runs


def check_set_hash(checks: list) -> str:
    """A short hash over what decides a score: every check's id, weight, kind and visibility, the source
    of the week's check modules and of the scoring helpers, the expected values they read, and the hidden
    data.

    Two runs with the same hash (and seed) ran the same checks the same way, so a local and an official
    result can be compared.
    """
    from grader.inside.probes import PROBES

    h = hashlib.sha256()
    modules = set(_SCORING_MODULES) | {probe.__module__ for probe in PROBES.values()}
    for check in sorted(checks, key=lambda c: c.id):
        h.update(json.dumps([check.id, check.weight, check.kind, check.visibility]).encode())
        modules.add(getattr(check.run, "__module__", "") or "")
    for name in sorted(m for m in modules if m):
        module = sys.modules.get(name) or importlib.import_module(name)
        try:
            h.update(inspect.getsource(module).encode())
        except (OSError, TypeError):
            h.update(name.encode())
    from grader.hidden import hidden_dir

    for path in sorted(hidden_dir().glob("week*.json")):
        h.update(path.read_bytes())
    for path in sorted(_EXPECTED.glob("*.json")):  # the expected values checks read as data
        h.update(path.read_bytes())
    return h.hexdigest()[:16]


def grader_version(checks: list) -> str:
    """The package version plus the check-set hash, e.g. "0.1.0+3fa2c9d01b7e4a55"."""
    return f"{package_version()}+{check_set_hash(checks)}"


def submission_result(
    *,
    week: int,
    seed: int,
    submission: str,
    checks: list,
    results: list[CheckResult],
    status: str = "graded",
    message: str = "",
    extra: dict[str, Any] | None = None,
) -> dict[str, Any]:
    """Assemble the contract's result JSON for one submission."""
    digest = check_set_hash(checks)
    score = sum(r.points for r in results)
    max_score = sum(r.max_points for r in results)
    out: dict[str, Any] = {
        "week": week,
        "score": round(score, 6),
        "max_score": round(max_score, 6),
        "status": status,
        "seed": seed,
        "grader_version": f"{package_version()}+{digest}",
        "check_set_hash": digest,
        "submission": submission,
        "checks": [r.to_json() for r in results],
    }
    if message:
        out["message"] = message
    if extra:
        out.update(extra)
    return out


def all_passed(result: dict[str, Any]) -> bool:
    """True when the submission was graded and every check passed (the CLI's exit status 0)."""
    return result.get("status") == "graded" and all(c["status"] == "passed" for c in result["checks"])


def loss_summary(results: list[CheckResult], problems: dict[str, list[str]]) -> str:
    """Why points were lost, in one line for the gradebook and the class summary ("" when none were):
    the files that did not load first (a missing file, a syntax error), then the checks that lost points."""
    lost = [r for r in results if r.points < r.max_points]
    if not lost:
        return ""
    parts = []
    if problems:
        parts.append("code that did not load: " + "; ".join(texts[0] for texts in problems.values() if texts))
    names = ", ".join(r.id for r in lost[:6]) + (f" and {len(lost) - 6} more" if len(lost) > 6 else "")
    parts.append(f"points lost on {len(lost)} of {len(results)} checks: {names}")
    return ". ".join(parts)
