"""Fake grading functions for the batch tests: behave according to the submission's ``answer.txt``.

``score N``  graded, N points of 10 over three checks   ``sleep S`` sleep S seconds, then ``score 5``
``hang``     never return (and leave a grandchild that   ``crash``   the grading process dies (exit 3)
             must be killed too; its pid in ``pidfile``)  ``raise``   the grading function raises
``invalid``  a result with status invalid                 ``garbage`` a reply that is not a result
``leak F``   copy the submission to a temporary folder (its path written to F), then hang
``flood N``  a result whose messages, details and report hold N bytes of hostile text
``under_load`` graded, but the machine kept one check from a verdict (grader.under_load)
"""

from __future__ import annotations

import base64
import os
import subprocess
import sys
import tempfile
import time


def _answer(task: dict) -> str:
    text = task["files"].get("answer.txt")
    return base64.b64decode(text).decode().strip() if text else "score 0"


def result_for(task: dict, score: float) -> dict:
    week = task["week"]
    checks = [{"id": f"week{week}.fake.a", "name": "first", "kind": "property", "points": min(score, 4.0),
               "max_points": 4.0, "status": "passed" if score >= 4 else "failed", "message": "",
               "details": {}},
              {"id": f"week{week}.fake.b", "name": "second", "kind": "scenario",
               "points": max(0.0, min(score - 4, 6.0)), "max_points": 6.0,
               "status": "passed" if score >= 10 else "failed", "message": "=HYPERLINK(\"x\")",
               "details": {"seed": task["seed"]}},
              {"id": f"week{week}.fake.c", "name": "third", "kind": "static", "points": 0.0,
               "max_points": 0.0,
               "status": "passed", "message": "", "details": {}, "visibility": "hidden"}]
    return {"week": week, "score": float(score), "max_score": 10.0, "status": "graded", "seed": task["seed"],
            "grader_version": "fake", "submission": task["student"], "checks": checks,
            "notices": list(task.get("notices") or [])}


def fake_grade(task: dict) -> dict:
    """The fake grading function (module level, so grading processes can import it)."""
    word, _, arg = _answer(task).partition(" ")
    if word == "score":
        return {"result": result_for(task, float(arg)), "html": f"<p>{task['student']} {arg}</p>"}
    if word == "sleep":
        time.sleep(float(arg))
        return {"result": result_for(task, 5.0), "html": "<p>slept</p>"}
    if word == "hang":
        child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(600)"])
        if arg:
            with open(arg, "w") as stream:
                stream.write(str(child.pid))
        time.sleep(600)
    if word == "crash":
        print("fake grader: about to die", flush=True)
        os._exit(3)
    if word == "raise":
        raise RuntimeError("the fake grader broke")
    if word == "leak":
        folder = tempfile.mkdtemp(prefix="simiam-batch-")       # what grade_task does with student code
        with open(os.path.join(folder, "go_to_goal.py"), "w") as stream:
            stream.write("# student code\n")
        with open(arg, "w") as stream:
            stream.write(folder)
        time.sleep(600)
    if word == "flood":
        size = int(arg)
        result = result_for(task, 5.0)
        blob = ("<img src=x onerror=alert(1)>\x1b[2J\ud800" * (size // 32 + 1))[:size]
        result["message"] = blob
        for check in result["checks"]:
            check["message"] = blob
            check["details"] = {"values": list(range(size // 8)), "text": blob}
        return {"result": result, "html": f"<p>{blob}</p>"}
    if word == "under_load":
        result = result_for(task, 4.0)
        result["checks"][1].update(status="error", points=0.0, message="graded under load: regrade: ...")
        result["under_load"] = {"regrade": True, "checks": [result["checks"][1]["id"]], "message": "..."}
        return {"result": result, "html": "<p>under load</p>"}
    if word == "invalid":
        result = result_for(task, 0.0)
        result.update(status="invalid", checks=[], score=0.0, message="go_to_goal.py line 3: invalid syntax")
        return {"result": result, "html": None}
    return {"nope": 1}


def count_calls(task: dict) -> dict:
    """Like fake_grade, but appends the student id to ``$BATCH_CALLS`` (to see who was regraded)."""
    with open(os.environ["BATCH_CALLS"], "a") as stream:
        stream.write(task["student"] + "\n")
    return fake_grade(task)
