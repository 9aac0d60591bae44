"""`grade selfcheck`: the course grades as meant, so CI on the solutions branch can refuse a bad change.

Three promises, each checked by grading (the same engine as official grading, hidden checks included
where they say so):

- the reference solutions of every week get full marks, hidden checks included;
- the stubs generated from them get zero on every coded part (a week with no coded part, week 1, only has
  to grade), and the committed assignments/ match what the generator makes of solutions/;
- every kept wrong version (COURSE/tests/data/wrong/*.patch, a `# aims:` line naming the checks it aims
  at, `none` for a correct alternative) loses exactly those checks and no other.

It prints one line per expectation, then per week how many kept wrong versions each check catches and
which checks catch none (a check no wrong version loses is not proven able to fail), and exits 1 when any
expectation failed. See docs/ci-selfcheck.yml. Under the solutions' line it prints the margin of each
scenario check (grader.margins): how far the reference's figures are from their limits; under a wrong
version's line, how far its figures are on the failing side of the scenario checks it aims at. A verdict
with little to spare is one a last bit could flip.
"""

from __future__ import annotations

import re
import tempfile
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from grader.grading import DEFAULT_SEED, ROOT, grade_submission
from grader.margins import passes, words
from grader.platforms.wrong_versions import MistakeError, apply_mistake
from grader.untrusted import printable


@dataclass
class Expectation:
    """One promise: grade `folder` as week `week` (with the hidden checks if `hidden`); `verdict` says
    what is wrong with the result, or None when it is as meant."""

    label: str
    week: int
    folder: Path
    hidden: bool
    verdict: Callable[[dict], str | None]
    margins: Callable[[dict], list[str]] | None = None  # the margin lines printed under the verdict
    wrong_version: bool = False           # a kept wrong version: what it lost counts toward coverage
    lost: frozenset[str] | None = None    # the checks it lost, once graded


def full_marks(result: dict) -> str | None:
    """None when every check passed with full points."""
    lost = [f"{c['id']} ({c['points']:g}/{c['max_points']:g}: {c['message'][:160]})"
            for c in result["checks"] if c["points"] < c["max_points"] or c["status"] != "passed"]
    if result["status"] != "graded":
        return f"not graded: {result.get('message', '')[:300]}"
    return "lost " + "; ".join(lost) if lost else None


def zero_points(result: dict) -> str | None:
    """None when no check gave any point (the stub of a week with coded parts)."""
    scored = [f"{c['id']} ({c['points']:g})" for c in result["checks"] if c["points"] > 0]
    return "the stub scores on " + ", ".join(scored) if scored else None


def loses_exactly(aims: frozenset[str]) -> Callable[[dict], str | None]:
    """A verdict: the result lost points on exactly the checks in `aims`."""
    def verdict(result: dict) -> str | None:
        if result["status"] != "graded":
            return f"not graded: {result.get('message', '')[:300]}"
        lost = {c["id"] for c in result["checks"] if c["points"] < c["max_points"]}
        if lost == aims:
            return None
        parts = []
        if aims - lost:
            parts.append("keeps the points of " + ", ".join(sorted(aims - lost)) + " it aims at")
        if lost - aims:
            parts.append("also loses " + ", ".join(sorted(lost - aims)))
        return "; ".join(parts)
    return verdict


def reference_margins(result: dict) -> list[str]:
    """One line per scenario check: each figure it judged, the run nearest its limit and what it has to
    spare (a check judging no figure, such as 'the simulator runs', says so)."""
    lines = []
    for c in result["checks"]:
        if c["kind"] != "scenario":
            continue
        entries = c.get("details", {}).get("margins")
        said = "; ".join(words(e) for e in entries) if entries else "no figure judged"
        lines.append(f"{c['id']}: {said}")
    return lines


def caught_margins(aims: frozenset[str]) -> Callable[[dict], list[str]]:
    """The figures on the failing side, per scenario check in `aims` (a run the code broke has none: the
    error is the verdict)."""
    def lines(result: dict) -> list[str]:
        out = []
        for c in result["checks"]:
            if c["kind"] != "scenario" or c["id"] not in aims:
                continue
            failing = [e for e in c.get("details", {}).get("margins") or [] if not passes(e)]
            said = "; ".join(words(e) for e in failing) if failing else f"no figure: {c['message'][:120]}"
            out.append(f"{c['id']}: {said}")
        return out
    return lines


def has_coded_parts(week: int) -> bool:
    """True when the week introduces code blocks (week 1 only runs the simulator)."""
    from simiam.course.weeks import get_week

    return bool(get_week(week).blocks)


def run_selfcheck(course: Path, weeks: list[int], wrong: Path | None = None, seed: int | None = None,
                  out=print) -> int:
    """Grade every expectation of the course (see the module docstring); 0 when all held, else 1."""
    from simiam.course.stubs import differences, generate

    if course.resolve() != ROOT.resolve():
        raise ValueError(f"the grader here is installed from {ROOT}, not from {course}: run selfcheck with "
                         f"the grader of that course (pip install -e {course})")
    seed = DEFAULT_SEED if seed is None else seed
    failures = 0
    generated = generate(course / "solutions")
    # a stub of a week not checked here is left alone; the generated migrate manifest belongs to every week
    stale = [d for d in differences(generated, course)
             if not re.search(r"week\d/", d) or any(f"week{w}/" in d for w in weeks)]
    for path in stale:
        out(f"FAIL  stubs: {path} differs from what solutions/ generates (python -m simiam.course.stubs)")
    failures += len(stale)
    graded: list[Expectation] = []
    with tempfile.TemporaryDirectory(prefix="simiam-selfcheck-") as tmp:
        for exp in _expectations(course, weeks, wrong, Path(tmp), generated.files, out):
            if exp is None:
                failures += 1
                continue
            failures += check_one(exp, seed, out)
            graded.append(exp)
    for week in weeks:
        out(coverage(week, [e.lost for e in graded
                            if e.wrong_version and e.week == week and e.lost is not None]))
    out(f"selfcheck: {'all expectations held' if not failures else f'{failures} failed'}")
    return 0 if failures == 0 else 1


def _expectations(course: Path, weeks: list[int], wrong: Path | None, tmp: Path, stubs: dict[str, str],
                  out) -> list[Expectation | None]:
    exps: list[Expectation | None] = []
    for week in weeks:
        exps.append(Expectation(f"solutions week{week} (hidden checks included)", week,
                                course / "solutions" / f"week{week}", True, full_marks, reference_margins))
        folder = tmp / "stubs" / f"week{week}"
        folder.mkdir(parents=True)
        for rel, text in stubs.items():
            if rel.startswith(f"assignments/week{week}/"):
                (folder / rel.rsplit("/", 1)[1]).write_text(text, encoding="utf-8")
        if has_coded_parts(week):
            exps.append(Expectation(f"stubs week{week} (zero on every coded part)", week, folder, True,
                                    zero_points))
        else:
            exps.append(Expectation(f"stubs week{week} (nothing to code: full marks)", week, folder, True,
                                    full_marks))
    wrong = wrong if wrong is not None else course / "tests" / "data" / "wrong"
    for n, patch in enumerate(sorted(wrong.glob("*.patch")) if wrong.is_dir() else []):
        name = printable(patch.stem, multiline=False)
        try:  # every bad wrong version is its own FAIL line, and the others still run
            mistake, folder = apply_mistake(patch, course / "solutions", tmp / "wrong" / str(n))
        except (MistakeError, OSError) as exc:
            out(f"FAIL  wrong {name}: {printable(str(exc), multiline=False)}")
            exps.append(None)
            continue
        if mistake.week not in weeks:
            continue
        if mistake.aims is None:
            out(f"FAIL  wrong {name}: no '# aims:' line naming the checks it must lose")
            exps.append(None)
            continue
        what = ", ".join(sorted(mistake.aims)) or "nothing (a correct alternative)"
        exps.append(Expectation(f"wrong {name} (loses {what})", mistake.week, folder, False,
                                loses_exactly(mistake.aims), caught_margins(mistake.aims),
                                wrong_version=True))
    return exps


def coverage(week: int, lost: list[frozenset[str]]) -> str:
    """One line: per check of `week`, how many of the kept wrong versions (what each `lost`) it catches,
    and the checks none catches. Kept versions are graded without the hidden checks, so a hidden check is
    named apart: the hidden runs of the same scenarios are proven by tests/grader/test_hidden_week*.py."""
    from grader.checks import checks_for_week

    checks = checks_for_week(week)
    counts = {c.id: sum(c.id in one for one in lost) for c in checks}
    caught = ", ".join(f"{cid} {n}" for cid, n in counts.items() if n)
    none = [c.id for c in checks if not counts[c.id] and c.visibility != "hidden"]
    hidden = [c.id for c in checks if not counts[c.id] and c.visibility == "hidden"]
    line = f"coverage week{week} ({len(lost)} kept wrong versions): {caught or 'no check catches one'}"
    line += f"; caught by none: {', '.join(none)}" if none else "; every visible check catches one"
    return line + (f" (hidden, not graded here: {', '.join(hidden)})" if hidden else "")


def check_one(exp: Expectation, seed: int, out=print) -> int:
    """Grade one expectation, print its line; 1 when it failed."""
    result = grade_submission(exp.week, exp.folder, seed=seed, hidden=exp.hidden)
    exp.lost = frozenset(c["id"] for c in result.get("checks", []) if c["points"] < c["max_points"])
    problem = exp.verdict(result)
    out(f"{'ok  ' if problem is None else 'FAIL'}  {exp.label}"
        f"{'' if problem is None else ': ' + problem}  [{result['score']:g}/{result['max_score']:g}]")
    if exp.margins is not None and result["status"] == "graded":
        for line in exp.margins(result):
            out(f"        margin {line}")
    return 0 if problem is None else 1
