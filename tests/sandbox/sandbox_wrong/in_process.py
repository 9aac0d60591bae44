"""The wrong design the sandbox replaces: import the submission into the grading process and call it.

`python in_process.py ATTACK_FOLDER FN JSON_ARGS` loads the folder with the course loader, calls FN, then
prints what a naive grader would conclude. Run it only in a throw-away process: the attacks win here.
"""

import json
import math
import sys

from simiam.course.loader import load_submission

EXPECTED = [3.8403846153846155, 2.3134615384615387]


def main() -> None:
    folder, fn, args = sys.argv[1], sys.argv[2], json.loads(sys.argv[3])
    sub = load_submission(folder, 1)
    value = getattr(sub.module("differential_drive"), fn)(**args)
    print("math.sqrt(4) ->", math.sqrt(4.0))
    if isinstance(value, (list, tuple)):
        same = len(value) == 2 and all(v == e for v, e in zip(value, EXPECTED, strict=True))
    else:
        same = value == EXPECTED
    print("answer == expected ->", same)
    print("value ->", repr(value)[:200])
    print("DONE")


if __name__ == "__main__":
    main()
