"""Official grading on a platform: the secret baked into a bundle, and one upload graded with it.

A bundle (Gradescope zip, PrairieLearn image) carries two files besides the package:

- ``config.json`` (public): the week, how hidden checks are shown, and what the bundle was built from;
- ``secret/`` (root-only: the folder 0700, its files 0600): ``grading.json`` with the course's secret seed,
  and ``hidden/weekN.json``, the week's hidden variant set.

The grading process reads the secret as root. Student code never can: in the bubblewrap sandbox the folder
is simply not there (only /usr, the Python environment and the spliced submission are bound), and without
bubblewrap the worker drops to a dedicated unprivileged uid, for which a 0700 root folder is closed.

Where neither holds (no bubblewrap sandbox, and a grader that is not root: Coursera's containers when they
forbid namespaces, any platform like them), student code would run under the grader's own uid with nothing
between them: it could read the secret and write the feedback file the platform takes as the grade. Official
grading then fails closed (issue 30 item 4): `grade_upload` raises NoSandbox, with a message for the course
staff saying what to enable, before any student code runs; the entrypoints report a grader failure, never
a grade. `isolation_note` in every result that was graded says which isolation held.
"""

from __future__ import annotations

import json
import os
import stat
import tempfile
from dataclasses import dataclass
from pathlib import Path

from grader.batch.zips import SubmissionRefused
from grader.inside.caps import clip as cap  # student output and messages are attacker-sized
from grader.platforms.intake import collect

SECRET_FORMAT = "simiam-secret/1"
CONFIG_FORMAT = "simiam-bundle/1"
GRADESCOPE_VISIBILITY = ("hidden", "after_due_date", "after_published", "visible")


class BundleBroken(RuntimeError):
    """The bundle's own files are missing or unreadable: an instructor's problem, never a student's."""


class NoSandbox(BundleBroken):
    """This machine would run student code under the grader's own uid with no sandbox: official grading
    refuses (the message, for the course staff, says what to enable)."""


def refuse_unsandboxed() -> None:
    """NoSandbox unless student code can be kept from the grader here: bubblewrap works, or the grader runs
    as root with a spare uid mapped (the worker then drops to a dedicated uid that cannot read the secret or
    the results; a root with no uid to drop to, as in a single-uid user namespace, is refused too)."""
    from grader.sandbox import isolation
    from grader.sandbox.capabilities import is_root

    works, why = isolation.bwrap_works()
    if works:
        return
    if is_root():
        if isolation.pick_uid() is not None:
            return
        why += "; and though the grader is root, no spare uid is mapped here for the worker to drop to"
    uid = os.geteuid() if hasattr(os, "geteuid") else "unknown"
    raise NoSandbox(
        f"official grading refused: student code would run under the grader's own uid ({uid}) with no "
        f"sandbox ({why}), so it could read the secret seed and hidden set and write the feedback file "
        "itself. Nothing was graded. To grade here, enable one of: (1) namespaces for bubblewrap in the "
        "grading container (a grader that is not root needs unprivileged user namespaces, which Docker's "
        "default seccomp profile refuses: --security-opt seccomp=unconfined, or a platform setting that "
        "allows them); (2) run the grader as root, so that student code runs under a dedicated unprivileged "
        "uid. Or grade this week on Gradescope or PrairieLearn, which run the grader as root. See "
        "docs/platforms.md (isolation per platform).")


@dataclass(frozen=True)
class Secret:
    """What official grading needs and students must not see."""

    week: int
    seed: int
    hidden_dir: Path


def write_secret(folder: Path, week: int, seed: int, hidden_file: Path | None) -> Path:
    """Write `folder`/grading.json and `folder`/hidden/weekN.json (a copy of `hidden_file`), owner-only."""
    hidden = folder / "hidden"
    hidden.mkdir(parents=True, exist_ok=True)
    (folder / "grading.json").write_text(
        json.dumps({"format": SECRET_FORMAT, "week": week, "seed": seed}, indent=1), encoding="utf-8")
    if hidden_file is not None:
        (hidden / f"week{week}.json").write_bytes(hidden_file.read_bytes())
    lock_down(folder)
    return folder


def lock_down(folder: Path) -> None:
    """Folders 0700 and files 0600 under `folder`: readable only by their owner (root on a platform)."""
    for path in [folder, *folder.rglob("*")]:
        path.chmod(0o700 if path.is_dir() else 0o600)


def read_secret(folder: Path) -> Secret:
    """The secret of a bundle; BundleBroken when it is missing, malformed, or readable by others."""
    path = folder / "grading.json"
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        mode = stat.S_IMODE(folder.stat().st_mode) | stat.S_IMODE(path.stat().st_mode)
    except (OSError, ValueError) as exc:
        raise BundleBroken(f"the bundle's secret {path} cannot be read ({exc})") from None
    if not isinstance(data, dict) or data.get("format") != SECRET_FORMAT:
        raise BundleBroken(f"{path} is not a {SECRET_FORMAT} file")
    if mode & 0o077:
        raise BundleBroken(f"{folder} is readable by other users (mode {oct(mode)}): run setup again, or "
                           f"chmod -R go-rwx {folder}")
    week, seed = data.get("week"), data.get("seed")
    if type(week) is not int or type(seed) is not int:
        raise BundleBroken(f"{path}: week and seed must be integers")
    return Secret(week, seed, folder / "hidden")


def read_config(path: Path) -> dict:
    """The bundle's public config.json."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise BundleBroken(f"the bundle's {path} cannot be read ({exc})") from None
    if not isinstance(data, dict) or data.get("format") != CONFIG_FORMAT:
        raise BundleBroken(f"{path} is not a {CONFIG_FORMAT} file")
    return data


def grade_upload(upload: Path, secret: Secret, fill_from: Path | None = None,
                 note_filled: bool = True) -> dict:
    """Grade the upload folder of one student with the bundle's seed and hidden set (every check).
    Course files missing from the upload are taken from `fill_from` (the handout) when it is given, with a
    notice for each unless `note_filled` is false (a platform whose students cannot submit those files).

    Returns the contract's result; a refused upload (no course files, hostile zip, ...) raises
    SubmissionRefused with the reason to show the student, and NoSandbox (before any student code runs)
    where student code would run under the grader's own uid with no sandbox."""
    refuse_unsandboxed()
    from grader.grading import grade_submission
    from simiam.course.shipped import files_to_write, missing_note

    # The hidden checks read their data from $SIMIAM_HIDDEN: point it at the secret, never the package.
    os.environ["SIMIAM_HIDDEN"] = str(secret.hidden_dir)
    if fill_from is not None:  # the course's versions of earlier weeks' parts, for scenarios (grader.earlier)
        os.environ["SIMIAM_HANDOUT"] = str(fill_from)
    filled = []
    with tempfile.TemporaryDirectory(prefix="simiam-upload-") as tmp:
        skipped: list[str] = []
        folder = Path(tmp) / f"week{secret.week}"
        if fill_from is not None and not files_to_write(secret.week) and _empty(upload):
            # a week with nothing to write (week 1): a question with no editor submits no file at all, and
            # what is graded is the handout itself
            folder.mkdir()
        else:
            folder = collect(upload, secret.week, folder, skipped)
        if fill_from is not None:
            # only the files the student writes nothing in this week: a missing file to write is named as
            # missing by the grader, not silently replaced by its placeholder
            for path in sorted(fill_from.glob("*.py")):
                if not (folder / path.name).exists() and path.name not in files_to_write(secret.week):
                    (folder / path.name).write_bytes(path.read_bytes())
                    filled.append(path.name)
        result = grade_submission(secret.week, folder, seed=secret.seed, hidden=True, sandbox="auto",
                                  official=True)
    result["submission"] = "your upload"     # not the grader's temporary path
    result.setdefault("notices", []).extend(missing_note(secret.week, name, True)
                                             for name in filled if note_filled)
    result["notices"][:0] = skipped
    return result


def _empty(upload: Path) -> bool:
    return upload.is_dir() and not any(upload.iterdir())


def installed_answers() -> list[str]:
    """Files of the installed simiam distribution that would give answers away (a hidden variant set, a
    reference solution): student code can read the environment, so a bundle refuses to run with them."""
    from importlib.metadata import PackageNotFoundError, files

    try:
        shipped = [str(f) for f in files("simiam") or []]
    except PackageNotFoundError:
        return []
    return [f for f in shipped if f.startswith(("solutions/", "instructor_tools/"))
            or (f.startswith("grader/hidden/") and f.endswith(".json"))]


def main(argv: list[str] | None = None) -> int:
    """`python -m grader.platforms.official --check-installed`: exit 1 if the installed package holds
    answers (the PrairieLearn image runs this while it is built)."""
    import argparse
    import sys

    parser = argparse.ArgumentParser(prog="python -m grader.platforms.official")
    parser.add_argument("--check-installed", action="store_true", required=True)
    parser.parse_args(argv)
    answers = installed_answers()
    for name in answers:
        print(f"the installed package holds {name}", file=sys.stderr)
    return 1 if answers else 0


if __name__ == "__main__":
    raise SystemExit(main())

__all__ = ["BundleBroken", "NoSandbox", "Secret", "SubmissionRefused", "cap", "grade_upload", "lock_down",
           "read_config", "read_secret", "write_secret"]
