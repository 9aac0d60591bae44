"""Coursera: a custom grader image (Coursera's v2 contract) for a week, and the image's entrypoint.

    grade package coursera week3 --out coursera-week3/ [--seed N] [--part-id ID]

writes coursera-week3/, the build folder Coursera takes (zip its contents, Dockerfile at the root, or
`docker build` it): Dockerfile (Debian + this package), dist/simiam-*.whl, config.json, handout/ (fills in
a file the student writes nothing in this week and did not upload), secret/ (the seed and the week's hidden
set: in the image owned by the unprivileged user the grader runs as, 0700, closed to every other user) and
simiam-coursera-grade, the entrypoint.

Coursera runs the image once per submission, without root, with the learner's upload in the read-only
/shared/submission/ and the assignment part in the environment variable `partId`. The entrypoint runs
`python -m grader.platforms.coursera run`, which grades the upload (loose files, a week folder or one zip)
with every check, hidden ones included, and writes /shared/feedback.json: `fractionalScore` (the points over
the maximum, in [0, 1]), `feedback` (plain text) and `"feedbackType": "HTML"` with /shared/htmlFeedback.html,
the per-check table learners see. Hidden checks count, but their message only says that they are hidden.
"""

from __future__ import annotations

import argparse
import contextlib
import html
import json
import os
import shutil
import sys
import tempfile
import traceback
from pathlib import Path

from grader.batch.store import write_atomic
from grader.platforms.bundle import stage_common
from grader.platforms.handout import copy_handout
from grader.platforms.official import (
    NoSandbox,
    SubmissionRefused,
    cap,
    grade_upload,
    read_config,
    read_secret,
)
from simiam.course.weeks import hidden_variants

TEMPLATES = Path(__file__).with_name("templates")
FEEDBACK_CHARS = 20_000      # the plain-text feedback (shown only where the HTML is not)
PAGE_CHARS = 500_000         # the HTML page, student output included, stays a page
PART_ID_CHARS = 64


def build(week: int, out: Path, course: Path, seed: int, part_id: str | None = None) -> dict:
    """Write the image's build folder of `week` into the new folder `out`; return its config."""
    if part_id is not None and not (0 < len(part_id) <= PART_ID_CHARS and part_id.isascii()
                                    and part_id.replace("_", "").replace("-", "").isalnum()):
        raise ValueError(f"--part-id {part_id!r}: Coursera part ids are short words such as 'Zb6wb'")
    if out.exists() and any(out.iterdir()):
        raise ValueError(f"{out} already exists and is not empty: remove it or choose another --out")
    with tempfile.TemporaryDirectory(prefix="simiam-coursera-") as tmp:
        stage = Path(tmp)
        # Coursera shows every result at once: hidden checks keep their points, never their details
        wheel, config = stage_common(week, course, seed, "hidden", stage)
        config["coursera_part_id"] = part_id
        (stage / "config.json").write_text(json.dumps(config, indent=1), encoding="utf-8")
        copy_handout(week, course, stage / "handout")
        dockerfile = (TEMPLATES / "coursera_Dockerfile").read_text(encoding="utf-8")
        (stage / "Dockerfile").write_text(dockerfile.format(week=week, wheel=wheel.name), encoding="utf-8")
        shutil.copy(TEMPLATES / "coursera_entrypoint.sh", stage / "simiam-coursera-grade")
        (stage / "simiam-coursera-grade").chmod(0o755)
        out.mkdir(parents=True, exist_ok=True)
        for part in sorted(stage.iterdir()):
            shutil.move(str(part), out / part.name)
    return config


# ---- inside the grading container ----------------------------------------------------------------------

def feedback(result: dict, config: dict) -> tuple[dict, str]:
    """feedback.json's content and the HTML page for one result of the grader."""
    from grader.platforms.prairielearn import results_json

    # PrairieLearn's results already hold what every platform shows: the score over the maximum, the
    # notes, which isolation held, and one test per check with hidden checks' messages withheld
    shown = results_json(result)
    if not shown.get("gradable"):
        return refused(str((shown.get("format_errors") or ["your submission could not be loaded"])[0]))
    week = int(result.get("week", config.get("week", 0)))
    head = f"Week {week}: {result.get('score', 0):g} / {result.get('max_score', 0):g} points"
    hidden = int(config.get("hidden_checks", 0))
    hidden_line = "" if not hidden else (
        f"{hidden} of the checks {'is' if hidden == 1 else 'are'} hidden ({hidden_variants(week)}): "
        f"{'its' if hidden == 1 else 'their'} points count, {'its' if hidden == 1 else 'their'} details are "
        "not shown.")
    notes = shown["message"].splitlines()[1:]        # its first line is the points, said in `head`
    rows = [(t["points"] >= t["max_points"], t) for t in shown["tests"]]
    text = "\n".join(line for line in [head, *notes, hidden_line, *(
        f"{'ok' if ok else 'FAILED'}  {t['description'] or t['name']}  {t['points']:g}/{t['max_points']:g}"
        f": {t['message']}" for ok, t in rows)] if line)
    esc = html.escape
    page = [f"<h2>{esc(head)}</h2>", *(f"<p>{esc(n)}</p>" for n in notes)]
    if hidden_line:
        page.append(f"<p>{esc(hidden_line)}</p>")
    page.append("<table><tr><th></th><th>check</th><th>points</th><th>message</th></tr>")
    page += [f"<tr><td>{'ok' if ok else 'FAILED'}</td><td>{esc(t['description'] or t['name'])}<br><code>"
             f"{esc(t['name'])}</code></td><td>{t['points']:g} / {t['max_points']:g}</td>"
             f"<td>{esc(t['message'])}</td></tr>" for ok, t in rows]
    page.append("</table>")
    if shown.get("output"):
        page.append(f"<p>What your code printed:</p><pre>{esc(shown['output'])}</pre>")
    payload = {"fractionalScore": float(shown["score"]), "feedback": cap(text, FEEDBACK_CHARS),
               "feedbackType": "HTML"}
    return payload, _page("\n".join(page))


def refused(reason: str) -> tuple[dict, str]:
    """Feedback for an upload that could not be graded at all: no points, and the reason."""
    text = "Your submission could not be graded: " + cap(reason, 2000)
    page = _page(f"<p>{html.escape(text)}</p>")
    return {"fractionalScore": 0.0, "feedback": text, "feedbackType": "HTML"}, page


def _page(body: str) -> str:
    return ("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>simiam feedback</title>\n"
            f"<style>{_STYLE}</style></head>\n<body>\n{cap(body, PAGE_CHARS)}\n</body></html>\n")


_STYLE = ("table{border-collapse:collapse} th,td{border:1px solid #ccc;padding:3px 6px;vertical-align:top;"
          "text-align:left} pre{white-space:pre-wrap}")


def run(shared: Path, home: Path, part_id: str | None) -> int:
    """Grade shared/submission into shared/feedback.json and shared/htmlFeedback.html with the image's files
    in `home` (config.json, secret/, handout/). A failure of the grader itself still writes a feedback that
    says so (the traceback goes to stderr, which only course staff see) and returns non-zero: 1, or 3 where
    student code would run under the grader's own uid with no sandbox (official.NoSandbox: refused before
    any student code runs). The feedback comes from the grader's own result only."""
    try:
        config = read_config(home / "config.json")
        secret = read_secret(home / "secret")
        expected = config.get("coursera_part_id")
        if expected and part_id != expected:
            payload, page = refused(f"this grader grades week {secret.week} (part {expected}), but the "
                                    f"upload came to part {cap(part_id or 'none', PART_ID_CHARS)}: submit it "
                                    f"to the week-{secret.week} part of the assignment")
        else:
            try:
                result = grade_upload(shared / "submission", secret, fill_from=home / "handout")
                payload, page = feedback(result, config)
            except SubmissionRefused as why:
                payload, page = refused(str(why))
        # the page first: feedback.json names it, so it must be complete when feedback.json appears
        write_atomic(shared / "htmlFeedback.html", page)
        write_atomic(shared / "feedback.json", json.dumps(payload, allow_nan=False) + "\n")
        print(f"graded: fractionalScore {payload['fractionalScore']:.4f}", file=sys.stderr)
        return 0
    except NoSandbox as exc:   # fail closed: no student code ran; the staff's log says what to enable
        print(f"simiam grader: {exc}", file=sys.stderr)
        _failed(shared, "The grader is not set up to run code safely on this grading machine, so your code "
                        "was not run and nothing was graded; your course staff can see why and will regrade.")
        return 3
    except Exception:   # the grader's own failure: say so, keep the traceback for the staff's log
        traceback.print_exc(file=sys.stderr)
        _failed(shared, "The grader itself failed, not because of your code; your instructor can see why and "
                        "will regrade.")
        return 1


def _failed(shared: Path, text: str) -> None:
    """The feedback of a grading that failed: this text and 0 points, replacing whatever feedback.json and
    page are there (the entrypoint, too, trusts no feedback after a non-zero exit)."""
    with contextlib.suppress(OSError):
        (shared / "htmlFeedback.html").unlink()
    write_atomic(shared / "feedback.json", json.dumps({"fractionalScore": 0.0, "feedback": text}) + "\n")


def main(argv: list[str] | None = None) -> int:
    """`python -m grader.platforms.coursera run --shared /shared --home /opt/simiam` (the entrypoint's)."""
    p = argparse.ArgumentParser(prog="python -m grader.platforms.coursera")
    p.add_argument("what", choices=("run",))
    p.add_argument("--shared", type=Path, default=Path("/shared"))
    p.add_argument("--home", type=Path, default=Path("/opt/simiam"))
    args = p.parse_args(argv)
    return run(args.shared, args.home, os.environ.get("partId"))


if __name__ == "__main__":
    sys.exit(main())
