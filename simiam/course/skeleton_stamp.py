"""The skeletons' stamp: what the packaged skeletons were generated from, so that a grader in a checkout
can tell in a millisecond that they are still up to date with solutions/.

`python -m simiam.course.stubs` writes `simiam/course/skeletons/stamp.json` with the sha256 of every file
it read (each declared week's `solutions/weekN/*.py`, and `placeholders.py`) and of every skeleton it
wrote. `up_to_date(solutions)` hashes the same files again and compares: equal means the skeletons are
what the generator wrote from exactly these inputs. Anything else (an edited or added solution file, a
hand-edited skeleton, a missing or unreadable stamp) is not an answer: the grader then regenerates every
week and compares, as it always did, which names the stale files (or finds that the edit changed no
skeleton). The generator's own code is not in the stamp: tests/course/test_stubs.py regenerates in full.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

SKELETONS = Path(__file__).with_name("skeletons")
STAMP = SKELETONS / "stamp.json"
PLACEHOLDERS = Path(__file__).with_name("placeholders.py")


def digest(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def stamp_text(solutions: dict[str, bytes], skeletons: dict[str, str]) -> str:
    """The stamp for the generator's inputs (`solutions`: {"weekN/file.py": bytes}) and the skeletons it
    generates from them ({"weekN/file.py": text})."""
    stamp = {
        "about": "written by `python -m simiam.course.stubs`: sha256 of what the skeletons were generated "
                 "from and of the skeletons (simiam/course/skeleton_stamp.py)",
        "placeholders": digest(PLACEHOLDERS.read_bytes()),
        "solutions": {name: digest(data) for name, data in sorted(solutions.items())},
        "skeletons": {name: digest(text.encode("utf-8")) for name, text in sorted(skeletons.items())},
    }
    return json.dumps(stamp, indent=1) + "\n"


def _hashes(folder: Path, weeks: set[str]) -> dict[str, str]:
    """{"weekN/file.py": sha256} of the .py files in folder/weekN for each week named in the stamp."""
    return {f"{week}/{p.name}": digest(p.read_bytes())
            for week in sorted(weeks) for p in sorted((folder / week).glob("*.py"))}


def up_to_date(solutions: Path, skeletons: Path | None = None) -> bool:
    """True when the stamp in `skeletons` (default: the packaged ones) matches the files in `solutions`
    and `skeletons` exactly (the same files, the same bytes). False means "not known": regenerate and
    compare."""
    skeletons = SKELETONS if skeletons is None else skeletons
    try:
        stamp = json.loads((skeletons / "stamp.json").read_text(encoding="utf-8"))
        expected_solutions, expected_skeletons = stamp["solutions"], stamp["skeletons"]
        if not (isinstance(expected_solutions, dict) and isinstance(expected_skeletons, dict)):
            return False
        return (
            stamp["placeholders"] == digest(PLACEHOLDERS.read_bytes())
            and _hashes(solutions, {k.split("/")[0] for k in expected_solutions}) == expected_solutions
            and _hashes(skeletons, {k.split("/")[0] for k in expected_skeletons}) == expected_skeletons
        )
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return False
