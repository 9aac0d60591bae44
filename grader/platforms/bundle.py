"""What every bundle carries, whatever the platform: the package wheel, the secret, the public config.

`stage_common` builds the wheel from a clean copy of the course (refusing one that holds answers), writes
the secret (seed and the week's hidden set, owner-only) and config.json (the week, how hidden checks are
shown, and the check-set hash the bundle was built with, hidden set included). Before anything is shipped,
the course's reference solution is graded exactly as the bundle will grade (that seed, that hidden set,
every check): a bundle that would not give it full marks is refused.
"""

from __future__ import annotations

import contextlib
import json
import os
import secrets
from collections.abc import Iterator
from pathlib import Path

from grader.platforms.official import CONFIG_FORMAT, GRADESCOPE_VISIBILITY, write_secret
from grader.platforms.wheel import answers_in, build_wheel


def new_seed() -> int:
    """A secret seed for official grading, when the instructor names none."""
    return secrets.randbelow(2**31)


@contextlib.contextmanager
def hidden_set(folder: Path) -> Iterator[None]:
    """Grade and hash with the hidden set in `folder` (the one the bundle carries) for a while."""
    before = os.environ.get("SIMIAM_HIDDEN")
    os.environ["SIMIAM_HIDDEN"] = str(folder)
    try:
        yield
    finally:
        if before is None:
            del os.environ["SIMIAM_HIDDEN"]
        else:
            os.environ["SIMIAM_HIDDEN"] = before


def course_hidden_file(course: Path, week: int) -> Path | None:
    """The course's hidden set of `week`: $SIMIAM_HIDDEN/weekN.json if that is set, else
    COURSE/instructor_tools/hidden/weekN.json; None when the week has none."""
    env = os.environ.get("SIMIAM_HIDDEN")
    path = (Path(env) if env else course / "instructor_tools" / "hidden") / f"week{week}.json"
    return path if path.is_file() else None


def build_config(week: int, hidden_visibility: str, hidden_dir: Path) -> dict:
    """The bundle's public config: what it grades and how hidden checks are shown."""
    from grader.checks import checks_for_week
    from grader.result import check_set_hash, package_version

    if hidden_visibility not in GRADESCOPE_VISIBILITY:
        raise ValueError(f"hidden checks' visibility must be one of {', '.join(GRADESCOPE_VISIBILITY)}")
    checks = checks_for_week(week)
    with hidden_set(hidden_dir):
        digest = check_set_hash(checks)
    return {"format": CONFIG_FORMAT, "week": week, "hidden_visibility": hidden_visibility,
            "max_score": sum(c.weight for c in checks), "checks": len(checks),
            "hidden_checks": sum(c.visibility != "visible" for c in checks),
            "package_version": package_version(), "check_set_hash": digest}


def stage_common(week: int, course: Path, seed: int, hidden_visibility: str, into: Path) -> tuple[Path, dict]:
    """Wheel, secret and config.json in `into` (shared by the Gradescope zip and the PrairieLearn image)."""
    from grader.grading import grade_submission
    from grader.platforms.selfcheck import full_marks

    wheel = build_wheel(course, into / "dist")
    answers = answers_in(wheel)
    if answers:
        raise ValueError(f"the wheel built from {course} holds answers ({', '.join(answers[:5])}): a bundle "
                         "must not ship them; fix the package data in pyproject.toml")
    secret = write_secret(into / "secret", week, seed, course_hidden_file(course, week))
    config = build_config(week, hidden_visibility, secret / "hidden")
    with hidden_set(secret / "hidden"):
        result = grade_submission(week, course / "solutions" / f"week{week}", seed=seed, hidden=True)
    problem = full_marks(result)
    if problem:
        raise ValueError(f"this bundle would not give solutions/week{week} full marks ({problem}); "
                         "is the week's hidden set missing? Nothing was written")
    config["wheel"] = wheel.name
    (into / "config.json").write_text(json.dumps(config, indent=1), encoding="utf-8")
    return wheel, config
