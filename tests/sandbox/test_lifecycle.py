"""When the grading process itself dies, its workers die with it (no orphan keeps burning CPU)."""

from __future__ import annotations

import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest
from sandbox_helpers import AS_ROOT

from grader.sandbox.runner import _uid_alive

GRADER = """
import os, sys, threading
sys.path.insert(0, {here!r})
from pathlib import Path
from sandbox_helpers import make_submission, PROBES
from grader.sandbox.limits import Limits
from grader.sandbox.session import StudentSession
s = StudentSession(1, make_submission(Path({base!r}), "infinite_loop"), Limits(call_seconds=30),
                   sandbox={mode!r}, probes="sandbox_probes", extra_paths=(str(PROBES),))
s.load()
print(s._worker.plan.uid, s._work.path.parent, flush=True)
threading.Timer(0.3, lambda: os._exit(9)).start()  # the grader dies while the student's loop runs
s.call("probe", name="attack", args={{}})
"""


@pytest.mark.skipif(not AS_ROOT, reason="needs the dedicated uid to find the worker")
def test_workers_die_with_the_grader(mode, shared_dir):
    script = GRADER.format(here=str(Path(__file__).parent), base=str(shared_dir), mode=mode)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60)
    assert done.returncode == 9, done.stderr
    uid, work = int(done.stdout.split()[0]), Path(done.stdout.split()[1])
    shutil.rmtree(work, ignore_errors=True)  # a killed grader cannot clean up after itself
    deadline = time.monotonic() + 5
    while _uid_alive(uid) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not _uid_alive(uid)
