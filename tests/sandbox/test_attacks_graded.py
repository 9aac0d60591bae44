"""The attack suite end to end: each attack is spliced into week 2's uni_to_diff block (a complete week-2
submission otherwise), graded with grade_submission, and must score no more than its honest behaviour earns
(the attacks answer wrongly, crash or hang, so 0 on the check) with a clear message. Forgery attempts
also leave the output folder as the grader wrote it.
"""

from __future__ import annotations

import json
import os
import socket
import threading
import time
from pathlib import Path

import pytest
from sandbox_helpers import graded_attack

from grader.grading import grade_submission
from grader.sandbox.isolation import BWRAP
from grader.sandbox.limits import Limits
from grader.sandbox.session import _choose

REPO = Path(__file__).resolve().parents[2]
CHECK = "week2.uni_to_diff.round_trip"
# 1 s per call keeps the hanging attacks short; every honest call takes milliseconds (at most 0.03 s measured
# with both cores saturated by busy loops), and the checks' own property calls have 2 s.
LIMITS = Limits(call_seconds=1.0, total_seconds=20.0)
SANDBOXED = _choose("auto") == BWRAP


def only_bwrap(test):
    """Holds only inside bubblewrap (documented in the subprocess note): marked `sandbox`, skipped without."""
    skip = pytest.mark.skipif(not SANDBOXED, reason="holds only inside bubblewrap (documented)")
    return pytest.mark.sandbox(skip(test))


def grade(folder: Path, only: str = CHECK, **kw) -> tuple[dict, dict]:
    result = grade_submission(2, folder, only=only, limits=LIMITS, **kw)
    return result, {c["id"]: c for c in result["checks"]}[only]


@pytest.fixture(scope="module")
def honest_points() -> float:
    result, check = grade(REPO / "solutions" / "week2")
    assert check["status"] == "passed"
    return check["points"]


@pytest.mark.parametrize("name, status, fragment", [
    ("sys_exit", "failed", "sys.exit(0)"),
    ("os_exit", "error", "exit status 0"),
    ("kill_parent", "failed", "your vel_r was 0"),
    ("base_exception", "failed", "Boom: no score for you"),
    ("monkeypatch", "failed", "your vel_r was 0"),   # the robot the probe builds is patched away too
    ("liar", "failed", "a Whatever object"),
    ("nan", "failed", "NaN"),
    ("inf", "failed", "infinity"),
    ("huge", "failed", "too large"),
    ("allocate", "failed", "MemoryError"),
    ("fork_bomb", "failed", "your vel_r was 0"),
    ("infinite_loop", "timeout", "did not answer in time"),
    ("sleep", "timeout", "did not answer in time"),
])
def test_attack_scores_no_more_than_honest(tmp_path, honest_points, name, status, fragment):
    result, check = grade(graded_attack(tmp_path, name))
    assert honest_points > 0
    assert (check["points"], check["status"]) == (0, status)
    assert fragment in check["message"]
    assert result["score"] == 0 and result["status"] == "graded"


def test_printed_results_are_not_the_score(tmp_path):
    out = tmp_path / "reports"
    result, check = grade(graded_attack(tmp_path, "fake_output"), out_dir=out)
    assert check["points"] == 0 and result["score"] == 0
    assert "100/100" in result["student_output"] and '"score": 10.0' in result["student_output"]
    html = (out / "week2.html").read_text()  # printed HTML is shown as text, never as markup
    assert '<h1 id="forged">' not in html and "<script>alert(1)" not in html
    assert "&lt;h1 id=&#34;forged&#34;&gt;" in html  # it is there, escaped


def test_flooding_output_is_truncated(tmp_path):
    result, check = grade(graded_attack(tmp_path, "flood_output"))
    assert check["points"] == 0 and "your vel_r was 0" in check["message"]
    assert len(result["student_output"]) <= 4000


def test_forged_files_never_replace_the_result(tmp_path):
    out = tmp_path / "reports"
    folder = graded_attack(tmp_path, "forge_files", target=out, delay=0.5)
    result, check = grade(folder, out_dir=out)
    written = (out / "week2.json").read_text()
    time.sleep(1.0)  # the detached writers would have woken up by now
    assert (out / "week2.json").read_text() == written
    assert json.loads(written)["score"] == 0 == check["points"]
    assert sorted(p.name for p in out.iterdir()) <= ["week2.html", "week2.json"]


@only_bwrap
def test_reading_the_solution_from_disk_gets_nothing(tmp_path, honest_points):
    result, check = grade(graded_attack(tmp_path, "read_solutions", repo=REPO))
    assert (REPO / "solutions" / "week2" / "differential_drive.py").exists()
    assert check["points"] == 0 < honest_points and "your vel_r was 0" in check["message"]


def test_asking_a_server_for_the_answer_gets_nothing(tmp_path):
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(4)
    connections = []

    def answer() -> None:  # would hand out the right wheel speeds to anyone who asks
        while True:
            try:
                conn, _ = server.accept()
            except OSError:
                return
            connections.append(1)
            with conn:
                v, w, R, L = json.loads(conn.makefile().readline())
                wheels = [(2 * v + w * L) / (2 * R), (2 * v - w * L) / (2 * R)]
                conn.sendall(json.dumps(wheels).encode() + b"\n")

    threading.Thread(target=answer, daemon=True).start()
    try:
        result, check = grade(graded_attack(tmp_path, "network", port=server.getsockname()[1]))
    finally:
        server.close()
    assert check["points"] == 0 and connections == []


def test_raised_robot_limits_do_not_reach_the_physics(tmp_path):
    from simiam.course.weeks import spec_for_week

    traces: dict = {}
    scenario = "week2.go_to_angle.reaches_theta_d"
    result, check = grade(graded_attack(tmp_path, "robot_limits"), only=scenario, traces=traces)
    assert traces, "the scenario recorded no trace"
    max_vel = spec_for_week(2).max_vel
    for trace in traces.values():
        applied = [abs(x) for x in trace["steps"]["vel_r"] + trace["steps"]["vel_l"]]
        assert max(applied) <= max_vel + 1e-12
    assert check["points"] == 0


def test_a_whole_week_with_an_exit_mid_run(tmp_path):
    attacked = grade_submission(2, graded_attack(tmp_path, "os_exit"), limits=LIMITS)
    assert attacked["status"] == "graded" and attacked["score"] < attacked["max_score"]
    for check in attacked["checks"]:
        if "uni_to_diff" in check["id"] or "go_to_angle" in check["id"]:
            assert check["points"] == 0, check


def test_code_outside_the_blocks_is_reported_and_never_run(tmp_path, honest_points):
    result, check = grade(graded_attack(tmp_path, "exit_at_import"))
    assert check["points"] == honest_points  # the os._exit at import time was not spliced in
    assert any("differential_drive.py" in n and "outside the code blocks" in n for n in result["notices"])


def test_a_forged_estimate_does_not_move_the_robot(tmp_path):
    scenario = "week2.go_to_angle.reaches_theta_d"
    honest, honest_check = grade(REPO / "solutions" / "week2", only=scenario)
    result, check = grade(graded_attack(tmp_path, "pose"), only=scenario)
    assert honest_check["points"] > 0 and check["points"] == 0


@pytest.mark.parametrize("name, fragment", [("os_exit", "exit status 0"), ("kill_parent", "your vel_r was 0"),
                                            ("fork_bomb", "your vel_r was 0"), ("sys_exit", "sys.exit(0)")])
def test_without_bubblewrap_too(tmp_path, name, fragment):
    if name == "kill_parent" and os.geteuid() != 0:
        pytest.skip("documented: without root, subprocess mode runs the worker under the grader's uid")
    result, check = grade(graded_attack(tmp_path, name), sandbox="subprocess")
    assert result["isolation"] == "subprocess" and "no bubblewrap" in result["isolation_note"]
    assert check["points"] == 0 and fragment in check["message"]


def test_a_huge_finite_debug_value_keeps_the_report_and_the_points(tmp_path):
    """Issue 22 item 3: week 5's blend stretched to ±1e308 (its heading, and so the run, unchanged): the
    report is written, its plot says what is off the chart, and the check keeps its points."""
    import mistakes

    out = tmp_path / "reports"
    folder = mistakes.build("attacks/graded", "huge_debug", tmp_path, 5)
    result = grade_submission(5, folder, only="week5.blending.reach_goal", out_dir=out)
    check = result["checks"][0]
    assert (check["status"], check["points"]) == ("passed", check["max_points"])
    assert "values off the chart (beyond ±1,000,000)" in (out / "week5.html").read_text()
