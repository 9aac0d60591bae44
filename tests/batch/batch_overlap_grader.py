"""A fake grading function split in two phases (grader.batch.grading_process.overlapped), for the pool
tests: it behaves according to the submission's ``answer.txt``. ``F`` is a file path.

``score N``           graded, N points                     ``mark F``          first phase creates F; score 5
``report-waits F S``  its report waits (up to 8 s) for F,  ``report-crash F``  its report waits for F, then
                      says whether F appeared, sleeps S s                     the grading process dies
``report-hang``       its report never ends                ``first-crash F``   first phase creates F, dies
``first-raise``       the first phase raises

Every first phase appends the student id to ``$BATCH_CALLS`` when that is set (who was graded again).
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable

from batch_fake_grader import _answer, result_for

from grader.batch.grading_process import overlapped


def _appears(path: str, seconds: float = 8.0) -> bool:
    end = time.monotonic() + seconds
    while not os.path.exists(path):
        if time.monotonic() > end:
            return False
        time.sleep(0.02)
    return True


def first_phase(task: dict) -> Callable[[], dict]:
    word, _, arg = _answer(task).partition(" ")
    if os.environ.get("BATCH_CALLS"):
        with open(os.environ["BATCH_CALLS"], "a") as stream:
            stream.write(task["student"] + "\n")
    arg, _, extra = arg.partition(" ")
    if word in ("mark", "first-crash"):
        with open(arg, "w"):
            pass
        if word == "first-crash":
            os._exit(4)
    if word == "first-raise":
        raise RuntimeError("the first phase broke")
    score = float(arg) if word == "score" else 5.0

    def report() -> dict:
        result = result_for(task, score)
        if word == "report-waits":
            result["message"] = "overlapped" if _appears(arg) else "the next task never began"
            time.sleep(float(extra or 0))
        if word == "report-crash":
            _appears(arg)
            os._exit(3)
        if word == "report-hang":
            time.sleep(600)
        return {"result": result, "html": f"<p>{task['student']}</p>"}
    return report


@overlapped(first_phase)
def overlap_grade(task: dict) -> dict:
    return first_phase(task)()


def serial_grade(task: dict) -> dict:
    """The same grading without the declared first phase: what a grading process that ignores the split
    (writes each report before it asks for the next task) does. The overlap test must catch it."""
    return first_phase(task)()
