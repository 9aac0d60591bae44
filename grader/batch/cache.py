"""When a submission needs grading again: the cache key (submission content, grader, seed).

Each per-student result stores its key under ``result["batch"]["cache_key"]``. A rerun skips a student
whose stored key equals the new one, so a batch killed half-way resumes where it stopped, and changing
the seed, the grader or the submission regrades exactly what changed.

The grader's identity is a fingerprint of the installed grading code (``grader/`` except the batch
plumbing, ``simiam/``, and the assignment stubs next to them when installed from a checkout), not only the
version string: an instructor who fixes a check without bumping the version still gets a regrade.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

from grader.batch.stored import well_formed

_SUFFIXES = {".py", ".j2", ".html", ".xml", ".json", ".css", ".js", ".txt"}
# Batch plumbing does not change a grade, except task.py, which calls the grader and rewrites paths.
# grader/practice/weekN.json: the practice sets, which no official grade runs (grade --practice only)
_NOT_GRADING = ("grader/batch/", "grader/practice/week")
_GRADING_TOO = ("grader/batch/task.py",)
# Statuses worth keeping: a timeout or crash may be the machine's fault, so it is retried on a rerun.
FINAL_STATUSES = ("graded", "invalid")


def _package_version() -> str:
    """The version a single grading states too (simiam.__version__, which the distribution is built with)."""
    from grader.result import package_version

    return package_version()


def grader_fingerprint() -> str:
    """``<version>+<12 hex>``: the package version (grader.result.package_version, as in a single
    grading's version) and a hash of every file that can change a grade. Every file of a batch states
    this one string as its grader version.

    Computed afresh on each call (about 20 ms), never cached: a long-lived process (a notebook running
    several batches) must see a check fixed in between.
    """
    import grader
    import simiam

    roots = [Path(grader.__file__).parent, Path(simiam.__file__).parent]
    checkout = roots[0].parent
    roots += [checkout / "assignments"] if (checkout / "assignments").is_dir() else []
    digest = hashlib.sha256()
    for root in roots:
        for path in sorted(root.rglob("*")):
            rel = f"{root.name}/{path.relative_to(root).as_posix()}"
            if (path.suffix not in _SUFFIXES or not path.is_file() or "__pycache__" in path.parts
                    or (rel.startswith(_NOT_GRADING) and rel not in _GRADING_TOO)):
                continue
            digest.update(rel.encode() + b"\x00" + hashlib.sha256(path.read_bytes()).digest())
    return f"{_package_version()}+{digest.hexdigest()[:12]}"


def cache_key(week: int, seed: int, hidden: bool, submission_sha256: str, grader: str,
              hidden_set: str = "") -> str:
    """The key a stored result must carry to be reused. ``hidden_set`` is the digest of the hidden set
    run (grader.hidden.identity): an edited ``instructor_tools/hidden/weekN.json`` regrades everyone."""
    material = json.dumps({"format": 2, "week": week, "seed": seed, "hidden": hidden,
                           "submission": submission_sha256, "grader": grader, "hidden_set": hidden_set},
                          sort_keys=True)
    return hashlib.sha256(material.encode()).hexdigest()


def is_fresh(stored: dict | None, key: str) -> bool:
    """True when ``stored`` (a per-student result, or None) can be reused for ``key``: a final status, the
    same key, and a shape the class files can be built from (grader.batch.stored: a malformed one is
    regraded, never trusted)."""
    if not isinstance(stored, dict) or stored.get("status") not in FINAL_STATUSES or not well_formed(stored):
        return False
    batch = stored.get("batch")
    return isinstance(batch, dict) and batch.get("cache_key") == key
