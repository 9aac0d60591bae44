"""The comparer against copydetect on the test class: how each ranks the planted copies.

    pip install --target /tmp/cd-env copydetect       # its wheel and dependencies, outside the project
    PYTHONPATH=.:/tmp/cd-env python benchmarks/similarity_copydetect.py

Both read the same text: the week-3 class of tests/similarity (the reference solution, three independent
solutions, three planted copies, two untouched stubs), each student's code blocks with the handout's
lines blanked (grader.similarity.submitted), the handout's blocks as copydetect's boilerplate. copydetect
runs at its defaults (noise threshold 25 characters, guarantee 30: k = 25, window 6) through its own
tokenizer and fingerprints (copydetect.utils, copydetect.detector.compare_files); a pair's score is the
larger of its two similarities, as its report ranks them. Printed: the best pairs of each, and what
tests/similarity's ranking rule finds wrong with each at thresholds 0.3-0.6.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "similarity"))

from similarity_class import build_class, ranking_problems  # noqa: E402

from grader.similarity.command import read_class  # noqa: E402
from grader.similarity.compare import compare  # noqa: E402
from grader.similarity.submitted import handout_blocks  # noqa: E402


def copydetect_scores(codes: list, k: int = 25, window: int = 6) -> dict[frozenset, float]:
    import numpy as np
    from copydetect import utils
    from copydetect.detector import compare_files

    class Prints:  # the fields compare_files reads (copydetect.CodeFingerprint builds them from a file)
        def __init__(self, text: str, boilerplate: object, win: int) -> None:
            self.filtered_code, self.offsets = utils.filter_code(text, "block.py")
            self.k = k
            self.hashes, self.hash_idx = utils.get_document_fingerprints(self.filtered_code, k, win,
                                                                         boilerplate)
            self.token_coverage = utils.get_token_coverage(self.hash_idx, k, len(self.filtered_code))

    handout = Prints("\n".join(b.compared for b in handout_blocks(3)), None, 1)
    boilerplate = np.array(sorted(handout.hashes))
    prints = {c.id: Prints("\n".join(b.compared for b in c.blocks), boilerplate, window) for c in codes}
    ids = sorted(prints)
    scores = {}
    for i, a in enumerate(ids):
        for b in ids[i + 1:]:
            if min(len(prints[a].filtered_code), len(prints[b].filtered_code)) >= k:
                _, (s1, s2), _ = compare_files(prints[a], prints[b])
                scores[frozenset((a, b))] = float(max(s1, s2))
    return scores


def main() -> int:
    codes = read_class(build_class(Path(tempfile.mkdtemp()) / "class"), 3).codes
    ours = {frozenset((p.a.id, p.b.id)): p.score for p in compare(codes, handout_blocks(3))}
    try:
        theirs = copydetect_scores(codes)
    except ImportError as exc:
        print(f"copydetect is not importable ({exc}); see this script's docstring", file=sys.stderr)
        return 2
    for name, scores in (("grade similarity", ours), ("copydetect 25/30", theirs)):
        best = sorted(scores.items(), key=lambda kv: -kv[1])[:5]
        print(f"{name}: " + "; ".join(f"{'/'.join(sorted(p))} {s:.2f}" for p, s in best))
        for threshold in (0.3, 0.4, 0.5, 0.6):
            problems = ranking_problems(scores, threshold)
            first = f" ({problems[0]})" if problems else ""
            print(f"  threshold {threshold}: {len(problems)} problems{first}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
