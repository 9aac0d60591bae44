"""A student as a platform's download shows them: who (an :class:`Identity`) and where their files are.

The readers of the three platforms' downloads (canvas_download, moodle_download, gradescope_export) each
turn an :class:`grader.batch.export_files.Export` into a :class:`Found` per student; grader/batch/intake.py
turns those into the runner's students. ``held`` says why the grader cannot tell which files are the
student's (two entries for one file, a submission without its folder): the instructor's problem, never
charged to the student.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

from grader.batch.identity import MAX_FILES, Identity


@dataclass
class Found:
    """One student of an export."""

    identity: Identity
    members: list[tuple[str, str]] = field(default_factory=list)  # (name in the export, path graded)
    notices: list[str] = field(default_factory=list)  # for the student's page
    held: str = ""  # for the instructor; "" = gradable

    def add_file_name(self, name: str) -> None:
        """Remember an export entry's name in the identity (the grade-back feedback files use it)."""
        if len(self.identity.files) < MAX_FILES:
            self.identity = dataclasses.replace(self.identity, files=(*self.identity.files, name))

    def hold(self, reason: str) -> None:
        """Mark the student held (the first reason stays; later ones are appended)."""
        self.held = f"{self.held}; {reason}" if self.held else reason


def rel_clashes(found: Found) -> None:
    """Hold a student whose export entries would give two files one path: the export cannot tell them
    apart, so the grader does not choose."""
    seen: dict[str, str] = {}
    for name, rel in found.members:
        key = rel.casefold()
        if key in seen:
            found.hold(
                f"two entries of the export give the file {rel}: {seen[key]} and {name}; which one "
                f"is the submission cannot be told from the download"
            )
        seen.setdefault(key, name)
