"""RemoteBrain (Seam 1 over the worker) drives the trusted simulator exactly as LocalBrain does in-process;
a brain that breaks the rules ends the run with the sandbox's or the simulator's error."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from grader.sandbox.errors import StudentError, WorkerDied
from grader.sandbox.limits import Limits
from grader.sandbox.session import RemoteBrain, StudentSession
from simiam.control.local_brain import LocalBrain
from simiam.course.loader import load_submission
from simiam.course.weeks import get_week, spec_for_week
from simiam.simulator import BrainError, Simulator
from simiam.world import load_world

REPO = Path(__file__).resolve().parents[2]
SETTINGS = {"goal": [0.5, 0.5], "v": 0.15}


def _run(brain, week: int = 3, seconds: float = 2.0) -> dict:
    cfg = get_week(week)
    sim = Simulator(load_world(cfg.world), brain, spec_for_week(week), dt=cfg.dt, start=cfg.start)
    trace = sim.run(seconds=seconds)
    if trace.ending.broken:  # the run ended at the brain's error, which the tests below look at
        raise trace.ending.error
    return trace.to_json()["steps"]


def test_remote_and_local_brains_give_the_same_trace(shared_dir, one_mode):
    local = _run(LocalBrain(load_submission(REPO / "solutions" / "week3", 3), get_week(3), SETTINGS))
    with StudentSession(3, REPO / "solutions" / "week3", sandbox=one_mode) as session:
        remote = _run(RemoteBrain(session, SETTINGS))
    assert remote == local  # bit for bit: floats cross the JSON channel exactly
    assert max(abs(x) for x in remote["x"]) > 0.01  # and the robot did move


def _broken(shared_dir: Path, replacement: str) -> Path:
    folder = shared_dir / "broken"
    shutil.copytree(REPO / "solutions" / "week3", folder)
    path = folder / "qb_supervisor.py"
    text = path.read_text()
    marker = "    def execute(self, dt):\n"
    assert marker in text
    path.write_text(text.replace(marker, marker + replacement, 1))
    for p in (folder, *folder.iterdir()):
        p.chmod(0o755 if p.is_dir() else 0o644)
    return folder


def test_a_supervisor_that_exits_mid_run_ends_the_run(shared_dir, one_mode):
    exit_later = "        if self.robot.encoders[0].ticks > 3:\n            import os; os._exit(0)\n"
    folder = _broken(shared_dir, exit_later)
    with StudentSession(3, folder, Limits(call_seconds=1.0), sandbox=one_mode) as session:
        with pytest.raises(WorkerDied, match="exit status 0"):
            _run(RemoteBrain(session, SETTINGS))


def test_a_supervisor_that_raises_names_its_line(shared_dir, one_mode):
    folder = _broken(shared_dir, "        raise ZeroDivisionError('oops')\n")
    with StudentSession(3, folder, sandbox=one_mode) as session:
        with pytest.raises(StudentError, match="qb_supervisor.py:.*ZeroDivisionError: oops"):
            _run(RemoteBrain(session, SETTINGS))


# the worker answers a step record with the writer it made for the run (grader.inside.record_writer),
# found here among the worker's objects and made to write what the forged LocalBrain.step returns (sent as
# JSON where it is not a record's types)
_WRITES_STEP = ("        import gc\n"
                "        for worker in gc.get_objects():\n"
                "            if type(worker).__name__ == '_Worker':\n"
                "                worker.write = lambda rid, worker=worker: worker.brain.step(None)\n")


def test_a_forged_command_is_refused_by_the_simulator_rules(shared_dir, one_mode):
    # Student code can rewrite the worker's own LocalBrain and step records, so the command is whatever it
    # likes...
    forge = ("        from simiam.control.local_brain import LocalBrain\n"
             "        LocalBrain.step = lambda self, readings: {'vel_r': 'fast', 'vel_l': 1e9}\n"
             + _WRITES_STEP)
    folder = _broken(shared_dir, forge)
    with StudentSession(3, folder, sandbox=one_mode) as session:
        with pytest.raises(BrainError, match="vel_r must be a finite number"):  # ...and checked here
            _run(RemoteBrain(session, SETTINGS))


def test_forged_debug_values_reach_the_trace_only_as_declared_kinds(shared_dir, one_mode):
    # ...and whatever a forged worker puts in debug, the trace keeps only declared names, of their kind
    junk = ("{'vel_r': 1.0, 'vel_l': 1.0, 'state': 'x' * 10000, 'debug': {'v': 'fast', 'w': [1.0], "
            "'theta_g': True, 'u_ao': [1, 2, 3], 'ir_points_wf': [[0.0] * 1000, [0.0] * 1000], "
            "'junk': list(range(1000))}}")
    forge = ("        from simiam.control.local_brain import LocalBrain\n"
             f"        LocalBrain.step = lambda self, readings: {junk}\n" + _WRITES_STEP)
    folder = _broken(shared_dir, forge)
    # each step carries about 1 MB of forged JSON back: 0.2 s with both cores busy, so 10 s per step
    with StudentSession(3, folder, Limits(call_seconds=10.0), sandbox=one_mode) as session:
        steps = _run(RemoteBrain(session, SETTINGS), seconds=0.5)
    assert "junk" not in steps and {len(s) for s in steps["state"][2:]} == {80}
    for name in ("v", "w", "theta_g", "u_ao", "ir_points_wf"):
        assert steps[name][2:] == [None] * (len(steps["t"]) - 2)
