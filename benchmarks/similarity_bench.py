"""`grade similarity` speed: a class of N week-3 submissions compared, and one hostile 5 MB block.

    python benchmarks/similarity_bench.py               # 400 students
    python benchmarks/similarity_bench.py --n 40
    PYTHONPATH=.:/tmp/cd-env python benchmarks/similarity_bench.py   # with copydetect beside it

The class is made in memory from the week-3 test data (the reference solution, three independent
solutions and three planted copies; each student's gains changed at random, seeded). Printed, in CPU
seconds of this process: reading every student's blocks, comparing all pairs, writing the page and the
JSON; then the hostile student (a 5 MB block in quickbot.py) alone; each against the baseline of the same
run, the standard library's tokenize over the same text. Where copydetect is importable (its wheel and
dependencies installed in a folder on PYTHONPATH: `pip install --target /tmp/cd-env copydetect`) its own
tokenizer and fingerprints (copydetect.utils.filter_code, get_document_fingerprints at its defaults) are
timed on the same texts, for the choice docs/batch.md explains. Nothing is asserted.
"""

from __future__ import annotations

import argparse
import io
import random
import re
import sys
import time
import tokenize
from pathlib import Path

from grader.similarity.compare import compare
from grader.similarity.page import report_json, similarity_html
from grader.similarity.submitted import handout_blocks, student_code
from simiam.machine import load_after_line, machine_line

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data" / "similarity" / "week3"
GAIN = re.compile(r"(self\.K[pid] *= *)[0-9.]+")


def _variants() -> list[dict[str, bytes]]:
    solution = {p.name: p.read_bytes() for p in (ROOT / "solutions" / "week3").glob("*.py")}
    out = [solution]
    for folder in sorted((DATA / "independent").iterdir()) + sorted((DATA / "planted").iterdir()):
        out.append({**solution, **{p.name: p.read_bytes() for p in folder.glob("*.py")}})
    return out


def make_class(n: int, seed: int = 1) -> dict[str, dict[str, bytes]]:
    """n students, each a variant with its gains changed at random."""
    rng = random.Random(seed)
    variants = _variants()
    students = {}
    for i in range(n):
        files = dict(variants[i % len(variants)])
        text = files["go_to_goal.py"].decode()
        files["go_to_goal.py"] = GAIN.sub(lambda m: m.group(1) + f"{rng.uniform(0.01, 9):.3f}", text).encode()
        students[f"s{i:04d}"] = files
    return students


def _cpu(action):  # noqa: ANN001, ANN202 - a timing helper
    start = time.process_time()
    value = action()
    return time.process_time() - start, value


def _stdlib_tokens(texts: list[str]) -> int:
    count = 0
    for text in texts:
        try:
            count += sum(1 for _ in tokenize.generate_tokens(io.StringIO(text).readline))
        except (tokenize.TokenError, SyntaxError):
            pass
    return count


def _copydetect(texts: list[str]) -> float | None:
    try:
        from copydetect import utils  # noqa: PLC0415 - optional, for the comparison only
    except ImportError:
        return None
    start = time.process_time()
    for text in texts:
        filtered, _ = utils.filter_code(text, "block.py")
        utils.get_document_fingerprints(filtered, 25, 1)     # copydetect's defaults: noise 25, guarantee 30
    return time.process_time() - start


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n", type=int, default=400, help="students in the class (default 400)")
    parser.add_argument("--common", type=int, default=None, help="as grade similarity --common (default: "
                        "the class size, nothing set aside: every copy of a variant pairs with every other)")
    parser.add_argument("--hostile-mb", type=float, default=5.0, help="size of the hostile block, MB")
    args = parser.parse_args(argv)
    print(machine_line("none (nothing of the students' code runs)"), flush=True)
    handout_blocks(3)     # the handout's blocks are read once per run: not part of any student's figure
    students = make_class(args.n)
    read_s, codes = _cpu(lambda: [student_code(sid, files, 3) for sid, files in students.items()])
    texts = [b.compared for c in codes for b in c.blocks]
    base_s, tokens = _cpu(lambda: _stdlib_tokens(texts))
    common = args.common or args.n
    compare_s, pairs = _cpu(lambda: compare(codes, handout_blocks(3), max_common=common))
    meta = {"week": 3, "threshold": 0.6, "k": 6, "window": 4, "common": common, "handout": "bench"}
    page_s, page = _cpu(lambda: (similarity_html(pairs, codes, {}, meta),
                                 report_json(pairs, codes, {}, meta)))
    flagged = sum(p.score >= 0.6 for p in pairs)
    print(f"baseline: stdlib tokenize over the class's blocks ({tokens} tokens): {base_s:.3f} s CPU")
    print(f"class of {args.n} (passages in more than {common} submissions set aside): read blocks "
          f"{read_s:.3f} s, compare {compare_s:.3f} s ({len(pairs)} pairs share a fingerprint, {flagged} "
          f"at 60 % or more), page and JSON {page_s:.3f} s, "
          f"page {len(page[0]) / 1024:.0f} KB; total {read_s + compare_s + page_s:.3f} s CPU = "
          f"{(read_s + compare_s) / base_s if base_s else float('nan'):.1f}x baseline (read + compare)")
    line = "        vel_r = (2 * v + w * L) / (2 * R)  # comment\n"
    block = line * int(args.hostile_mb * 1e6 / len(line))
    text = (ROOT / "solutions" / "week3" / "quickbot.py").read_text() + \
        "\nclass Z:\n    def f(self):\n        # START CODE BLOCK\n" + block + "        # END CODE BLOCK\n"
    hostile = {**students["s0000"], "quickbot.py": text.encode()}
    one_s, code = _cpu(lambda: compare([student_code("hostile", hostile, 3)], handout_blocks(3)))
    base1_s, _ = _cpu(lambda: _stdlib_tokens([block]))
    print(f"hostile student, a {len(block) / 1e6:.1f} MB block: {one_s:.3f} s CPU (read, cut to 16 KB, "
          f"fingerprinted); baseline: stdlib tokenize over the whole block {base1_s:.3f} s CPU")
    theirs = _copydetect(texts)
    if theirs is None:
        print("copydetect: not importable (pip install --target /tmp/cd-env copydetect; "
              "PYTHONPATH=.:/tmp/cd-env)")
    else:
        big = _copydetect([block])
        print(f"copydetect: the class's blocks {theirs:.3f} s CPU ({theirs / base_s:.1f}x baseline); "
              f"the whole {len(block) / 1e6:.1f} MB block {big:.3f} s CPU ({big / base1_s:.1f}x baseline)")
    print(load_after_line())
    return 0


if __name__ == "__main__":
    sys.exit(main())
