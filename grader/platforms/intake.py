"""Turn what a student uploaded to a platform into one folder the grader can splice.

Students upload in any layout: the loose files, their week folder, the whole course folder, or one zip of
any of these. The upload is hostile input: it is read with the batch runner's limits and checks
(grader.batch.submissions, grader.batch.zips: no links out, no zip slip, no bombs, size caps), the folder
holding the course files is found the same way, and only regular files are written into a fresh folder.
"""

from __future__ import annotations

from pathlib import Path

from grader.batch.names import check_paths
from grader.batch.submissions import STUDENT_FILES, find_root, pack, read_folder, skipped_note, unpack
from grader.batch.windows_names import leave_out
from grader.batch.zips import SubmissionRefused, read_zip
from simiam.course.weeks import get_week

__all__ = ["SubmissionRefused", "collect"]


def collect(upload: Path, week: int, into: Path, notices: list[str] | None = None) -> Path:
    """Write the student's week files from the platform's upload folder `upload` into `into` (created)
    and return it. Raises SubmissionRefused with a reason the student can act on. A file the grader does
    not use whose name is not UTF-8, and any file whose name cannot be written on Windows, is skipped
    and said in `notices`; names that only Windows or macOS would take for one file are refused."""
    if not upload.is_dir():
        raise SubmissionRefused("no submission was uploaded")
    skipped: list[str] = []
    files = read_folder(upload, skipped=skipped)
    if notices is not None:
        notices.extend(skipped_note(name) for name in skipped)
    if not any(p.rsplit("/", 1)[-1] in STUDENT_FILES for p in files):
        zips = [p for p in files if p.lower().endswith(".zip")]
        if len(zips) > 1:
            raise SubmissionRefused(f"the upload holds {len(zips)} zip files and no course files: "
                                    "upload one zip, or the .py files themselves")
        if zips:
            files = read_zip(upload.joinpath(*zips[0].split("/")))
    left_out: list[str] = []
    files = leave_out(files, left_out)  # aux.py, go_to_goal.py. ...: not writable on Windows
    if notices is not None:
        notices.extend(left_out)
    check_paths(list(files))  # two names Windows (or macOS) would take for one file
    _, files = find_root(files, week)
    wanted = {p: d for p, d in files.items() if "/" not in p}
    if not any(p in STUDENT_FILES for p in wanted):
        names = ", ".join(sorted(files)[:8]) or "nothing"
        expected = ", ".join(get_week(week).student_files)
        raise SubmissionRefused(f"none of the week-{week} files ({expected}) is in the upload; "
                                f"it holds {names}")
    into.mkdir(parents=True, exist_ok=True)
    return unpack(pack(wanted), into)
