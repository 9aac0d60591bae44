"""Grade one check of a week-2 submission in a fresh process and print, as JSON, the check's status and
message and the most memory this process held (for tests/sandbox/test_answer_bounds.py):

    python tests/sandbox/grading_memory.py FOLDER MODE CHECK [--wrong]

`--wrong` grades with the grader's side as it was before issue 22 (sandbox_wrong/unbounded_answers.py).
The peak is the kernel's VmHWM of this process, read from /proc: ru_maxrss would also count what the
process that started it held before the exec (Linux keeps the larger of the two).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path


def peak_mib() -> float:
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024
    raise RuntimeError("no VmHWM in /proc/self/status")


def main() -> None:
    folder, mode, check_id = sys.argv[1:4]
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))  # this checkout's grader, not one installed
    if "--wrong" in sys.argv[4:]:
        sys.path.insert(0, str(Path(__file__).resolve().parent))
        from sandbox_wrong import unbounded_answers

        unbounded_answers.install()
    from grader.grading import grade_submission
    from grader.sandbox.limits import Limits

    result = grade_submission(2, Path(folder), only=check_id, sandbox=mode,
                              limits=Limits(call_seconds=5.0, total_seconds=60.0))
    check = {c["id"]: c for c in result["checks"]}[check_id]
    print(json.dumps({"peak_mib": peak_mib(), "status": check["status"], "points": check["points"],
                      "message": check["message"]}))


if __name__ == "__main__":
    main()
