"""Who a submission belongs to, as the course platform or the roster says.

A batch reads a class from a platform's own download (Canvas, Moodle, Gradescope) or from one folder or
zip per student, and optionally a roster. Each student's :class:`Identity` is stored in their result
under ``batch.identity`` and is what the grade exports (Canvas and Moodle import CSVs, feedback zips) and
the late policy read. Everything in it came from files the instructor was handed, so it is bounded and
checked on the way in and again when read back (:meth:`Identity.from_json`).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

PLATFORMS = ("folder", "canvas", "moodle", "gradescope")
MAX_TEXT = 200            # characters of any one field; longer is cut
MAX_FILES = 500           # names of the files the export held for this student


def _text(value: object) -> str:
    """A bounded one-line string from whatever was stored (None and non-strings become "")."""
    if not isinstance(value, str):
        return ""
    return "".join(c if c.isprintable() else " " for c in value[:MAX_TEXT])


@dataclass(frozen=True)
class Identity:
    """One student of a batch.

    ``id`` is the key the batch uses everywhere (file names, ``--only``, roster rows): the folder or zip
    name for a class folder, the platform's user id for Canvas, the participant id for Moodle, the SID (or
    e-mail) for Gradescope. ``submitted_at`` is the platform's own submission time (ISO 8601 with an
    offset), "" when the platform did not say; file times are never used for it.
    """

    id: str
    name: str = ""           # display name: "Jane Doe"
    login: str = ""          # login or e-mail (Canvas SIS Login ID, Moodle/Gradescope e-mail)
    section: str = ""
    sis_id: str = ""         # Canvas SIS User ID, Moodle ID number
    platform: str = "folder"  # one of PLATFORMS
    platform_id: str = ""    # Canvas user id, Moodle participant id, Gradescope submission id
    submitted_at: str = ""   # ISO 8601 with offset, from the platform; "" unknown
    late_flag: bool = False  # the platform itself marked the submission late (Canvas's _LATE_)
    files: tuple[str, ...] = field(default_factory=tuple)  # the names the export held (feedback files)

    def to_json(self) -> dict:
        """Plain JSON for ``result["batch"]["identity"]``."""
        value = asdict(self)
        value["files"] = list(self.files)
        return value

    @classmethod
    def from_json(cls, value: object) -> Identity | None:
        """An Identity from a stored result, every field bounded; None if ``value`` holds no usable id."""
        if not isinstance(value, dict) or not isinstance(value.get("id"), str) or not value["id"]:
            return None
        files = value.get("files")
        platform = value.get("platform")
        return cls(id=value["id"][:MAX_TEXT], name=_text(value.get("name")), login=_text(value.get("login")),
                   section=_text(value.get("section")), sis_id=_text(value.get("sis_id")),
                   platform=platform if platform in PLATFORMS else "folder",
                   platform_id=_text(value.get("platform_id")), submitted_at=_text(value.get("submitted_at")),
                   late_flag=value.get("late_flag") is True,
                   files=tuple(_text(f) for f in files[:MAX_FILES]) if isinstance(files, list) else ())
