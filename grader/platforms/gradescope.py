"""Gradescope: build the autograder zip of a week, and what its run_autograder runs for each submission.

    grade package gradescope week3 --out autograder.zip [--seed N] [--hidden-visibility after_published]

The zip holds, at its root (Gradescope's autograder specification): `setup.sh`, `run_autograder`,
`config.json`, `dist/simiam-*.whl` (this checkout's package), `handout/` (the week's handout: it fills in a
file the student writes nothing in this week and did not upload) and `secret/` (the seed and the week's
hidden set, closed to every user but root by setup.sh). Gradescope unpacks it into /autograder/source.

    python -m grader.platforms.gradescope run --root /autograder     # run_autograder does this
    python -m grader.platforms.gradescope check --root /autograder   # setup.sh does this

`run` grades /autograder/submission (loose files, a week folder, the course folder or one zip) with every
check, hidden ones included, and writes /autograder/results/results.json: the score, one test per check
(name, score, max_score, status, output, visibility; hidden checks get the visibility chosen at build time),
and a top-level summary saying which isolation held.
"""

from __future__ import annotations

import argparse
import html
import os
import shutil
import stat
import sys
import tempfile
import time
import traceback
from pathlib import Path

from grader.batch.exports import gradescope_result
from grader.batch.store import write_json
from grader.inside.shorten import keep_ends
from grader.platforms.archive import write_zip
from grader.platforms.bundle import stage_common
from grader.platforms.handout import copy_handout
from grader.platforms.official import (
    BundleBroken,
    SubmissionRefused,
    cap,
    grade_upload,
    installed_answers,
    read_config,
    read_secret,
)
from simiam.course.weeks import hidden_variants

TEMPLATES = Path(__file__).with_name("templates")
MESSAGE_CHARS = 4000        # per test output; Gradescope shows it collapsed, students read the start
_WHEN = {"after_published": "once grades are published", "after_due_date": "after the due date",
         "hidden": "never (only your instructor does)", "visible": "right away"}


def build(week: int, out: Path, course: Path, seed: int, hidden_visibility: str = "after_published") -> dict:
    """Write the Gradescope autograder zip of `week` to `out`; return its config (plus the wheel's path)."""
    with tempfile.TemporaryDirectory(prefix="simiam-gradescope-") as tmp:
        stage = Path(tmp)
        wheel, config = stage_common(week, course, seed, hidden_visibility, stage)
        # the week's handout: what fills in a file the student writes nothing in and did not upload
        copy_handout(week, course, stage / "handout")
        shutil.copy(TEMPLATES / "gradescope_setup.sh", stage / "setup.sh")
        shutil.copy(TEMPLATES / "gradescope_run_autograder", stage / "run_autograder")
        files = {p.relative_to(stage).as_posix(): p.read_bytes()
                 for p in sorted(stage.rglob("*")) if p.is_file()}
        modes = {name: 0o600 for name in files if name.startswith("secret/")}
        write_zip(out, files, modes={**modes, "setup.sh": 0o755, "run_autograder": 0o755})
    return config


# ---- inside the Gradescope container -------------------------------------------------------------------

def results_json(result: dict, config: dict, seconds: float) -> dict:
    """Gradescope's results.json for one graded result (see the module docstring)."""
    export = gradescope_result(result)
    chosen = config.get("hidden_visibility", "after_published")
    for test, check in zip(export["tests"], [c for c in result.get("checks") or [] if isinstance(c, dict)],
                           strict=True):
        test["visibility"] = "visible" if check.get("visibility") == "visible" else chosen
        test["output"] = cap(test["output"], MESSAGE_CHARS)
        test["output_format"] = "text"
        test["name_format"] = "text"
    export.update(output=summary_html(result, config), output_format="simple_format",
                  test_output_format="text", test_name_format="text",
                  execution_time=int(round(seconds)), stdout_visibility="hidden",
                  extra_data=_extra(result, config))
    return export


def summary_html(result: dict, config: dict) -> str:
    """The top-level feedback: status, isolation, notices and the student's printed output (escaped)."""
    esc = html.escape
    lines = [f"<strong>Week {int(result.get('week', config['week']))}: "
             f"{result.get('score', 0):g} / {result.get('max_score', 0):g}</strong>"]
    if result.get("status") != "graded":
        lines.append(f"Your submission could not be graded: {esc(cap(result.get('message'), 2000))}")
    hidden = config.get("hidden_checks", 0)
    if hidden:
        when = _WHEN.get(str(config.get("hidden_visibility")), "later")
        vary = hidden_variants(config.get("week"))  # what this week's hidden checks vary
        lines.append(f"{hidden} of the checks are hidden ({esc(vary)}); you see their results {when}.")
    for note in (result.get("notices") or [])[:20]:
        lines.append("Note: " + esc(cap(note, 500)))
    isolation = result.get("isolation")
    if isolation:
        lines.append(f"Isolation ({esc(str(isolation))}): {esc(cap(result.get('isolation_note'), 1600))}")
    numerics = result.get("numerics")
    if isinstance(numerics, dict) and numerics.get("note"):  # the platform's CPU could not be pinned
        lines.append("Numerics: " + esc(cap(numerics.get("note"), 600)))
    printed = result.get("student_output")
    if printed:
        # its first and last lines, as the result keeps them (grader.sandbox.output), in Gradescope's room;
        # only what it printed during the visible checks: a hidden check's is in that check's test
        lines.append("What your code printed during the visible checks (its first and last lines):<pre>"
                     + esc(keep_ends(str(printed), 2000, whole_lines=True)) + "</pre>")
    return "\n".join(lines)


def _extra(result: dict, config: dict) -> dict:
    extra = {"grader_version": result.get("grader_version"), "isolation": result.get("isolation"),
             "status": result.get("status")}
    if result.get("check_set_hash") and result.get("check_set_hash") != config.get("check_set_hash"):
        extra["warning"] = "check set differs from the one the bundle was built with"
    return extra


def refused_json(reason: str, config: dict) -> dict:
    """results.json for an upload that could not be graded at all: 0 points and the reason."""
    return {"score": 0.0, "output": "Your submission could not be graded: " + html.escape(cap(reason, 2000)),
            "output_format": "simple_format", "stdout_visibility": "hidden", "tests": [],
            "extra_data": {"status": "refused"}}


def run(root: Path) -> int:
    """Grade root/submission into root/results/results.json. Never raises: an internal failure still writes
    a results.json that says so (and the traceback goes to stdout, which only instructors see)."""
    out = root / "results" / "results.json"
    began = time.monotonic()
    config: dict = {"week": 0, "hidden_visibility": "after_published"}
    try:
        close_metadata(root)
        config = read_config(root / "source" / "config.json")
        secret = read_secret(root / "source" / "secret")
        try:
            handout = root / "source" / "handout"
            result = grade_upload(root / "submission", secret,
                                  fill_from=handout if handout.is_dir() else None)
        except SubmissionRefused as refused:
            write_json(out, refused_json(str(refused), config))
            print(f"refused: {refused}")
            return 0
        payload = results_json(result, config, time.monotonic() - began)
        write_json(out, payload)
        print(f"graded: {result.get('score')} / {result.get('max_score')} ({result.get('status')}), "
              f"isolation {result.get('isolation')}")
        return 0
    except Exception as exc:   # the grader's own failure: never the student's, never silent
        traceback.print_exc(file=sys.stdout)
        write_json(out, {"score": 0.0, "stdout_visibility": "hidden", "tests": [],
                         "output": "The autograder itself failed, not because of your code; your "
                                   "instructor can see why and will regrade.",
                         "extra_data": {"error": type(exc).__name__}})
        return 1


def close_metadata(root: Path) -> None:
    """Close Gradescope's root/submission_metadata.json to every user but root before student code runs.
    It holds the student's earlier submissions with their whole results, hidden tests' output included,
    and Gradescope does not say who may read it: without bubblewrap the worker's uid might. The grader
    never reads it."""
    path = root / "submission_metadata.json"
    try:
        if stat.S_ISREG(os.lstat(path).st_mode):    # never through a link
            os.chmod(path, 0o600)
    except FileNotFoundError:
        pass
    except OSError as exc:   # grading goes on; the log (instructors only) says what stayed open
        print(f"could not close {path}: {exc}")


def check(root: Path) -> int:
    """setup.sh's last step: the bundle's files are readable by root, closed to others, and say what
    isolation this image gives student code."""
    from grader.sandbox.isolation import bwrap_works

    try:
        config = read_config(root / "source" / "config.json")
        secret = read_secret(root / "source" / "secret")
    except BundleBroken as exc:
        print(f"setup: {exc}", file=sys.stderr)
        return 1
    answers = installed_answers()
    if answers:
        print(f"setup: the installed package holds answers ({', '.join(answers[:5])})", file=sys.stderr)
        return 1
    works, why = bwrap_works()
    print(f"setup: week {secret.week}, {config['checks']} checks ({config['hidden_checks']} hidden, shown "
          f"{config['hidden_visibility']}), max score {config['max_score']:g}")
    print("setup: isolation " + ("bubblewrap" if works else f"subprocess with a dedicated uid ({why})"))
    if os.geteuid() != 0:
        print("setup: not root here, so student code keeps this user's uid and could read the secret")
    return 0


def main(argv: list[str] | None = None) -> int:
    """`python -m grader.platforms.gradescope run|check --root DIR` (what the bundle's scripts call)."""
    p = argparse.ArgumentParser(prog="python -m grader.platforms.gradescope")
    p.add_argument("what", choices=("run", "check"))
    p.add_argument("--root", type=Path, default=Path("/autograder"))
    args = p.parse_args(argv)
    return run(args.root) if args.what == "run" else check(args.root)


if __name__ == "__main__":
    sys.exit(main())
