"""A week-3 class for the similarity tests: the reference solution and three independent hand-written
solutions (tests/data/similarity/week3/independent), planted copies of them (planted/: ana's work with
names, comments and spacing changed; ben's with statements reordered; dana's own work but chen's
ensure_w), and two students who handed in the stub untouched."""

from __future__ import annotations

import shutil
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data" / "similarity" / "week3"
INDEPENDENT = ("ana", "ben", "chen")
PLANTED = {"ana_renamed": "ana", "ben_reordered": "ben", "dana": "chen"}   # copy -> whom it copied
STUBS = ("stub1", "stub2")


def build_class(folder: Path) -> Path:
    """Write the class folder (one sub-folder per student id) and return it."""
    folder.mkdir(parents=True, exist_ok=True)

    def student(sid: str, base: Path, own: Path | None = None) -> None:
        shutil.copytree(base, folder / sid, ignore=shutil.ignore_patterns("__pycache__", "README.md"))
        for f in own.iterdir() if own else ():
            shutil.copy(f, folder / sid / f.name)

    student("sol", ROOT / "solutions" / "week3")
    for sid in INDEPENDENT:
        student(sid, ROOT / "solutions" / "week3", DATA / "independent" / sid)
    for sid in PLANTED:
        student(sid, ROOT / "solutions" / "week3", DATA / "planted" / sid)
    for sid in STUBS:
        student(sid, ROOT / "assignments" / "week3")
    return folder


def is_copy(a: str, b: str) -> bool:
    """True for the pairs planted as copies."""
    return PLANTED.get(a) == b or PLANTED.get(b) == a


def ranking_problems(scores: dict[frozenset, float], threshold: float) -> list[str]:
    """What is wrong with the scores of every pair ({frozenset({a, b}): score}, absent = 0): each planted
    copy must score at least the threshold and above every other pair; the stubs' pair below it."""
    ids = ["sol", *INDEPENDENT, *PLANTED, *STUBS]
    pairs = [frozenset((a, b)) for i, a in enumerate(ids) for b in ids[i + 1:]]
    copies = [p for p in pairs if is_copy(*p)]
    others = [p for p in pairs if not is_copy(*p)]
    best_other = max(others, key=lambda p: scores.get(p, 0.0))
    out = []
    for p in copies:
        if scores.get(p, 0.0) <= scores.get(best_other, 0.0):
            out.append(f"copy {sorted(p)} scores {scores.get(p, 0.0):.3f}, not above the independent pair "
                       f"{sorted(best_other)} ({scores.get(best_other, 0.0):.3f})")
        if scores.get(p, 0.0) < threshold:
            out.append(f"copy {sorted(p)} scores {scores.get(p, 0.0):.3f}, below the threshold {threshold}")
    for p in others:
        if scores.get(p, 0.0) >= threshold:
            out.append(f"independent pair {sorted(p)} scores {scores.get(p, 0.0):.3f}, at or above the "
                       f"threshold {threshold}")
    stubs = scores.get(frozenset(STUBS), 0.0)
    if stubs > 0.05:
        out.append(f"the two untouched stubs score {stubs:.3f}; sharing only the handout must score ~0")
    return out
