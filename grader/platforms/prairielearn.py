"""PrairieLearn: an externally graded question for a week, its grader image, and the image's entrypoint.

    grade package prairielearn week3 --out pl-week3/ [--seed N] [--image NAME] [--timeout S]

writes

    pl-week3/question/           -> <course>/questions/simiam_week3/: info.json (externalGradingOptions),
                                    question.html (a file editor per file with a block new
                                    this week), starter/*.py
    pl-week3/serverFilesCourse/  -> <course>/serverFilesCourse/: simiam_week3/ (the secret seed and the
                                    week's hidden set; students never see serverFilesCourse)
    pl-week3/image/              -> `docker build -t NAME pl-week3/image`: Dockerfile (Debian + this
                                    package), the wheel, config.json, the handout, simiam-pl-grade

The image holds nothing secret, so it may be public (PrairieLearn pulls it from a registry); the seed and
the hidden set travel in the course repository's serverFilesCourse, which PrairieLearn copies to
/grade/serverFilesCourse/simiam_weekN for each job. The entrypoint closes that folder to every user but root
before any student code runs, then runs `python -m grader.platforms.prairielearn run --root /grade`: it
grades /grade/student and writes /grade/results/results.json in PrairieLearn's format: `score` in 0..1, one
test per check (name, description, points, max_points, message), `gradable: false` with `format_errors`
when nothing could be graded, and never more than PrairieLearn's 1 MB.
"""

from __future__ import annotations

import argparse
import json
import shutil
import sys
import tempfile
import traceback
import uuid
from pathlib import Path

import jinja2

from grader.batch.store import write_atomic
from grader.platforms.bundle import stage_common
from grader.platforms.handout import copy_handout
from grader.platforms.official import (
    BundleBroken,
    SubmissionRefused,
    cap,
    grade_upload,
    lock_down,
    read_config,
    read_secret,
)
from simiam.course.weeks import hidden_variants

TEMPLATES = Path(__file__).with_name("templates")
MAX_RESULTS_BYTES = 1_000_000          # PrairieLearn's documented limit on results.json
MESSAGE_CHARS = 4000
HIDDEN_MESSAGE = "hidden check (another goal, start pose or world): its details are not shown"
_UUID_NAMESPACE = uuid.UUID("5d0c1a3e-6b8f-4d0e-9a57-51a1a0c0e2b1")


def build(week: int, out: Path, course: Path, seed: int, image: str | None = None,
          timeout: int = 120) -> dict:
    """Write the question and the image folder of `week` into the new folder `out`; return the config."""
    if not 1 <= timeout <= 600:
        raise ValueError("--timeout must be between 1 and 600 seconds (PrairieLearn's limit)")
    if out.exists() and any(out.iterdir()):
        raise ValueError(f"{out} already exists and is not empty: remove it or choose another --out")
    image = image or f"simiam-week{week}"
    with tempfile.TemporaryDirectory(prefix="simiam-pl-") as tmp:
        stage = Path(tmp)
        img = stage / "image"
        wheel, config = stage_common(week, course, seed, "hidden", img)
        shutil.move(str(wheel), img / wheel.name)
        (img / "dist").rmdir()
        shared = f"simiam_week{week}"
        (stage / "serverFilesCourse").mkdir()
        shutil.move(str(img / "secret"), stage / "serverFilesCourse" / shared)
        dockerfile = (TEMPLATES / "prairielearn_Dockerfile").read_text(encoding="utf-8")
        (img / "Dockerfile").write_text(dockerfile.format(week=week, image=image, wheel=wheel.name),
                                        encoding="utf-8")
        shutil.copy(TEMPLATES / "prairielearn_entrypoint.sh", img / "simiam-pl-grade")
        (img / "simiam-pl-grade").chmod(0o755)
        question = stage / "question"
        starter = copy_handout(week, course, question / "starter")
        readme = (starter / "README.md").read_text(encoding="utf-8")
        (starter / "README.md").unlink()
        editable = editor_files(week, starter)
        # the image completes a submission with the files students have no editor for (provided code)
        shutil.copytree(starter, img / "starter")
        info = {"uuid": str(uuid.uuid5(_UUID_NAMESPACE, f"simiam/week{week}")),
                "title": f"Week {week}: {_title(readme)}", "topic": "QuickBot programming assignments",
                "tags": ["simiam", f"week{week}"], "type": "v3", "singleVariant": True,
                "gradingMethod": "External",
                "externalGradingOptions": {
                    "enabled": True, "image": image, "timeout": timeout, "serverFilesCourse": [f"{shared}/"],
                    "entrypoint": f"/usr/local/bin/simiam-pl-grade /grade/serverFilesCourse/{shared}"}}
        (question / "info.json").write_text(json.dumps(info, indent=2) + "\n", encoding="utf-8")
        env = jinja2.Environment(loader=jinja2.FileSystemLoader(TEMPLATES), autoescape=True,
                                 keep_trailing_newline=True)
        page = env.get_template("prairielearn_question.html.j2").render(
            week=week, title=_title(readme), files=editable, hidden=config["hidden_checks"] > 0,
            hidden_variants=hidden_variants(week))
        (question / "question.html").write_text(page, encoding="utf-8")
        out.mkdir(parents=True, exist_ok=True)
        for part in ("question", "serverFilesCourse", "image"):
            shutil.move(str(stage / part), out / part)
    config.update(image=image, files=editable)
    return config


def editor_files(week: int, starter: Path) -> list[str]:
    """The files the question opens an editor for: those holding a block new this week (the week's declared
    unit says which). Files with only earlier weeks' blocks are provided code, as in the handout: an editor
    for them would invite edits the grader reports and ignores."""
    from simiam.course.shipped import files_to_write

    return sorted(name for name in files_to_write(week) if (starter / name).is_file())


def _title(readme: str) -> str:
    first = readme.strip().splitlines()[0] if readme.strip() else ""
    return first.lstrip("# ").split(":", 1)[-1].strip() or "QuickBot"


# ---- inside the grading container ----------------------------------------------------------------------

def results_json(result: dict) -> dict:
    """PrairieLearn's results.json for one result of the grader (see the module docstring)."""
    if result.get("status") != "graded":
        return not_gradable(result.get("message") or "your submission could not be loaded")
    tests = []
    for check in result.get("checks") or []:
        hidden = check.get("visibility") != "visible"
        tests.append({"name": check.get("id", "check"), "description": str(check.get("name", "")),
                      "points": float(check.get("points", 0.0)),
                      "max_points": float(check.get("max_points", 0.0)),
                      "message": HIDDEN_MESSAGE if hidden else cap(check.get("message"), MESSAGE_CHARS)})
    max_score = float(result.get("max_score") or 0.0)
    score = float(result.get("score") or 0.0) / max_score if max_score > 0 else 0.0
    lines = [f"{result.get('score', 0):g} of {max_score:g} points"]
    lines += [f"note: {cap(n, 500)}" for n in (result.get("notices") or [])[:20]]
    lines.append(f"isolation: {result.get('isolation')}: {result.get('isolation_note') or ''}".strip())
    numerics = result.get("numerics")
    if isinstance(numerics, dict) and numerics.get("note"):  # the platform's CPU could not be pinned
        lines.append(f"numerics: {cap(numerics.get('note'), 600)}")
    return {"gradable": True, "score": min(1.0, max(0.0, score)), "message": "\n".join(lines),
            "output": cap(result.get("student_output") or "", MESSAGE_CHARS), "tests": tests}


def not_gradable(reason: str) -> dict:
    """Results for a submission PrairieLearn should not count as an attempt."""
    return {"gradable": False, "format_errors": [cap(reason, 2000)]}


def fit(payload: dict, limit: int = MAX_RESULTS_BYTES) -> str:
    """`payload` as JSON under `limit` bytes: messages are cut shorter until it fits."""
    for chars in (MESSAGE_CHARS, 1000, 200, 0):
        for test in payload.get("tests", []):
            test["message"] = cap(test["message"], chars) if chars else ""
        if "output" in payload:
            payload["output"] = cap(payload["output"], chars)
        text = json.dumps(payload, allow_nan=False)
        if len(text.encode()) <= limit:
            return text
    return json.dumps(not_gradable("the grading results were too large to report"))


def run(root: Path, home: Path, secret_dir: Path) -> int:
    """Grade root/student into root/results/results.json with the image's files in `home` and the secret in
    `secret_dir` (closed to everyone but root first). Never raises."""
    out = root / "results" / "results.json"
    try:
        read_config(home / "config.json")
        if secret_dir.is_dir():
            lock_down(secret_dir)      # a git checkout keeps no modes: close it before student code runs
        secret = read_secret(secret_dir)
        try:
            # the files without an editor never come from the student: filling them in is no news to them
            payload = results_json(grade_upload(root / "student", secret, fill_from=home / "starter",
                                                note_filled=False))
        except SubmissionRefused as refused:
            payload = not_gradable(str(refused))
        write_atomic(out, fit(payload))
        print(f"graded: gradable={payload['gradable']} score={payload.get('score')}")
        return 0
    except (BundleBroken, Exception):   # the grader's own failure: say so, keep the traceback for the log
        traceback.print_exc(file=sys.stdout)
        write_atomic(out, json.dumps(not_gradable(
            "the grader itself failed, not because of your code; your instructor will look into it")))
        return 1


def main(argv: list[str] | None = None) -> int:
    """`python -m grader.platforms.prairielearn run --root /grade --home /opt/simiam --secret DIR`."""
    p = argparse.ArgumentParser(prog="python -m grader.platforms.prairielearn")
    p.add_argument("what", choices=("run",))
    p.add_argument("--root", type=Path, default=Path("/grade"))
    p.add_argument("--home", type=Path, default=Path("/opt/simiam"))
    p.add_argument("--secret", type=Path, required=True, help="the folder with grading.json")
    args = p.parse_args(argv)
    return run(args.root, args.home, args.secret)


if __name__ == "__main__":
    sys.exit(main())
