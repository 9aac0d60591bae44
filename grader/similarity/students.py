"""Who ``grade similarity`` compares: SOURCE read with the batch's own intake.

SOURCE is whatever ``grade weekN --batch`` takes (grader/batch/intake.py): a class folder (one folder or
``.zip`` per student id) or a course platform's download as it comes (Canvas's submissions zip, Moodle's
download, Gradescope's export, zipped or extracted), with ``--roster`` laid over it as the batch lays it.
Each student's files are read by the batch's reader with its limits (grader.batch.submissions); a
student the batch would hold (an instructor-side problem) or refuse is listed as not compared, with why.
A compared student carries the name their Identity gives: the platform's, or the roster's when given.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from grader.batch.identity import MAX_TEXT
from grader.batch.intake import ClassList, IntakeError, IntakeOptions, read_class
from grader.batch.names import shown
from grader.batch.submissions import read_submission
from grader.similarity.submitted import StudentCode, student_code
from grader.untrusted import printable

MAX_UNPLACED = 200    # entries of a download that could not be placed, named in similarity.json


class SimilarityError(Exception):
    """The comparison cannot run (no such folder, no students); the message says why."""


@dataclass
class ComparedClass:
    """The students whose blocks are compared, those who are not (``{id: why}``), everyone's name
    (``{id: name}``, only those that have one) and what SOURCE was read as."""

    codes: list[StudentCode]
    not_compared: dict[str, str] = field(default_factory=dict)
    names: dict[str, str] = field(default_factory=dict)
    source: str = ""
    unplaced: list[str] = field(default_factory=list)


def read_source(source: Path, out: Path | None = None, roster: Path | None = None) -> ClassList:
    """SOURCE as the batch reads it (layout, students, ``roster`` laid over); ``out`` inside it is no
    student. SimilarityError when it cannot be read or holds nobody."""
    try:
        klass = read_class(source, IntakeOptions(roster=roster), out)
    except IntakeError as exc:
        raise SimilarityError(str(exc)) from None
    if not klass.students:
        raise SimilarityError(f"{source} has no student folders or .zip files" if klass.layout == "folder"
                              else f"{source}: no submissions found")
    return klass


def read_students(klass: ClassList, week: int) -> ComparedClass:
    """Every student's compared code blocks, read from the class the intake found."""
    compared = ComparedClass([], source=klass.described(),
                             unplaced=[shown(n) for n in klass.unplaced[:MAX_UNPLACED]])
    for student in klass.students:
        name = student.identity.name if student.identity is not None else ""
        name = printable(" ".join(name.split()), multiline=False)[:MAX_TEXT]   # from the download
        if name:
            compared.names[student.id] = name
        submission = read_submission(student, week=week)
        if submission.held is not None:
            compared.not_compared[student.id] = f"held (yours to sort out, as the batch holds it): " \
                                                f"{submission.held}"
            continue
        if submission.refused is not None:
            compared.not_compared[student.id] = submission.refused
            continue
        try:
            code = student_code(student.id, submission.files, week)
        except Exception as exc:  # noqa: BLE001 - one submission's text never stops the comparison
            compared.not_compared[student.id] = shown(f"its code blocks could not be read "
                                                      f"({type(exc).__name__}: {str(exc)[:300]})")
            continue
        code.name = name
        compared.codes.append(code)
    return compared
