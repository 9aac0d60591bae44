"""`grade --check ID --case ...` replays one failing case with what a student needs to debug it: what their
code printed, the traceback through their own files, and a Python snippet that calls their function with
exactly those inputs (and raises the same error when run). A timeout gets a replay line too."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import mistakes
import pytest

from grader.checks.answers import fmt
from grader.cli import main as grade_main
from grader.grading import grade_submission
from grader.sandbox.limits import Limits

ROOT = Path(__file__).resolve().parents[2]
CASE = "v=0.1,w=-2.0"
CHECK = "week2.uni_to_diff.round_trip"


def test_a_replayed_case_shows_prints_traceback_and_a_snippet_that_reproduces_it(tmp_path: Path,
                                                                                 capsys) -> None:
    folder = mistakes.build("submissions", "week2_uni_to_diff_prints_and_raises", tmp_path, 2, "week2")
    assert grade_main(["week2", str(folder), "--check", CHECK, "--case", CASE]) == 1
    out = capsys.readouterr().out
    assert "your code printed:\n  | uni_to_diff got 0.1 -2.0" in out
    line = next(i for i, t in enumerate((folder / "differential_drive.py").read_text().splitlines(), 1)
                if "WRONG" in t)
    assert (f'Traceback (your code, most recent call last):\n  File "differential_drive.py", line {line}, in '
            "uni_to_diff\n    scale = 1 / (w + 2)  # WRONG: divides by zero for w = -2\n"
            "ZeroDivisionError: float division by zero") in out
    code = out.split("run this Python next to your folder:\n\n", 1)[1]
    assert "uni_to_diff(robot, 0.1, -2.0)" in code
    ran = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert ran.returncode == 1 and "ZeroDivisionError" in ran.stderr
    assert "uni_to_diff got 0.1 -2.0" in ran.stdout


def test_the_snippet_of_a_wrong_answer_prints_what_the_check_saw(tmp_path: Path) -> None:
    folder = mistakes.build("wrong", "week3_integral_dt_again", tmp_path, 3, "week3")
    first = grade_submission(3, folder, seed=3, only="week3.pid.integral")
    case = first["checks"][0]["details"]["counterexample"]
    again = grade_submission(3, folder, seed=3, only="week3.pid.integral", case=case)
    details = again["checks"][0]["details"]
    assert "traceback" not in details
    code = details["snippet"]
    ran = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    _, w = ast.literal_eval(ran.stdout.strip().splitlines()[-1])
    assert f"your w was {fmt(w)}," in again["checks"][0]["message"]


def test_a_property_timeout_has_a_replay_line(tmp_path: Path) -> None:
    folder = mistakes.build("stuck", "week2_endless_loop", tmp_path, 2, "week2")
    # the loop is at the first call: only loading answers within 0.5 s (ms; see test_timeout_location)
    fast = Limits(call_seconds=0.5, total_seconds=20.0)
    result = grade_submission(2, folder, seed=1, only="week2.uni_to_diff.straight", limits=fast)
    check = result["checks"][0]
    assert check["status"] == "timeout"
    assert check["details"]["replay"].endswith("--check week2.uni_to_diff.straight --case 'v=0.1'")
    scenario = grade_submission(2, folder, seed=1, only="week2.go_to_angle.reaches_theta_d", limits=fast)
    assert scenario["checks"][0]["status"] == "timeout"
    assert scenario["checks"][0]["details"]["replay"].endswith("--check week2.go_to_angle.reaches_theta_d")


PROBE_CALLS = [  # one call of every probe, as the checks send them
    ("uni_to_diff", {"week": 2, "v": 0.1, "w": -2.0}),
    ("odometry", {"week": 2, "ticks": [[3, 1], [6, 2]], "start": [0.0, 0.0, 0.5]}),
    ("ir_distances", {"week": 2, "raw": [1375, 500, 300, 250, 200]}),
    ("ensure_w", {"week": 3, "v": 0.25, "w": 3.0}),
    ("go_to_goal", {"week": 3, "gains": {"Kp": 1, "Ki": 0, "Kd": 0}, "fresh": False,
                    "calls": [{"pose": [0, 0, 0], "goal": [1, 1], "v": 0.2, "dt": 0.05,
                               "memory": {"E_k": 0.3, "e_k_1": -0.2}}]}),
    ("transformation_matrix", {"week": 4, "x": 1.0, "y": -2.0, "theta": 0.5}),
    ("sensor_geometry", {"week": 4, "distances": [0.2] * 5, "pose": [0.1, -0.1, 1.0]}),
    ("avoid_obstacles", {"week": 4, "distances": [0.3, 0.1, 0.3, 0.3, 0.3], "pose": [0.3, -0.2, 0.7],
                         "v": 0.15}),
    ("blend", {"week": 5, "calls": [{"u_ao": [0.02, 0.3], "pose": [0.2, -0.1, 0.4], "goal": [1.2, -0.1]}]}),
    ("switching", {"week": 5, "cases": [{"state": "go_to_goal", "distances": [0.3, 0.3, 0.06, 0.3, 0.3],
                                         "at_goal": False}]}),
    ("follow_wall", {"week": 6, "distances": [0.1, 0.15, 0.3, 0.3, 0.3], "pose": [0.0, 0.0, 0.0],
                     "direction": "left", "d_fw": 0.15, "v": 0.15}),
    ("wall_settings", {"week": 6}),
    ("week7_sliding", {"week": 7, "direction": "left", "u_gtg": [0.0, 0.0], "u_ao": [0.3, -0.4],
                       "u_fw": [0.8, 0.6]}),
    ("week7_progress", {"week": 7, "goal": [1.1, 1.1], "estimate": [0.2, 0.3, 0.0], "d_prog": 1.0}),
    ("week7_progress_point", {"week": 7, "goal": [1.1, 1.1], "estimate": [0.2, 0.3, 0.0], "d_prog": 10.0}),
    ("week7_step", {"week": 7, "state": "go_to_goal", "fw_direction": "",
                    "events": {"at_goal": False, "at_obstacle": True, "unsafe": False,
                               "obstacle_cleared": False, "progress_made": False, "sliding_left": True,
                               "sliding_right": False},
                    "distances": [0.1, 0.12, 0.25, 0.3, 0.3]}),
]


@pytest.mark.parametrize(("name", "args"), PROBE_CALLS, ids=[n for n, _ in PROBE_CALLS])
def test_every_probe_has_a_snippet_that_runs(name: str, args: dict) -> None:
    from grader.inside.probes import PROBES
    from grader.replay import snippet

    assert {n for n, _ in PROBE_CALLS} == set(PROBES)
    code = snippet(str(ROOT / "solutions" / f"week{args['week']}"), (name, args))
    assert code is not None
    ran = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert ran.returncode == 0, ran.stderr
    assert ran.stdout.strip()


def test_replayed_output_cannot_drive_the_terminal() -> None:
    import io

    from grader.replay import print_replay

    out = io.StringIO()
    hostile = {"student_output": "hi\x1b[2J\x1b]0;pwned\x07\n", "checks": [
        {"details": {"traceback": "Traceback (your code, most recent call last):\nValueError: \x1b[31mred"}}]}
    print_replay(hostile, out)
    text = out.getvalue()
    assert "\x1b" not in text and "\x07" not in text
    assert "hi\\x1b[2J\\x1b]0;pwned\\x07" in text and "ValueError: \\x1b[31mred" in text
