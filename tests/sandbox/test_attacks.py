"""The attack suite, at the session level: each attack submission gets only what its honest behaviour earns
(the honest value, or a clear error) within the time limits, and the grading process and every other file
survive. Each test runs under bubblewrap and as a plain subprocess; the ones that only hold in a real
sandbox say so. End-to-end scores are in test_attacks_graded.py.
"""

from __future__ import annotations

import ctypes
import math
import os
import socket
import sys
import time
import uuid
from pathlib import Path

import numpy
import pytest
from sandbox_helpers import AS_ROOT, HONEST, attack, honest_probe, open_marker, says_it_reads

from grader.inside import seccomp
from grader.sandbox import validate
from grader.sandbox.errors import StudentError, StudentTimeout, WorkerDied
from grader.sandbox.isolation import BWRAP, SUBPROCESS
from grader.sandbox.limits import Limits
from grader.sandbox.runner import _uid_alive
from simiam import numerics

REPO = Path(__file__).resolve().parents[2]


def _needs_own_uid(mode: str) -> None:
    if mode != BWRAP and not AS_ROOT:
        pytest.skip("documented: without root, subprocess mode runs the worker as the grader's own user")


def _uid(session) -> int | None:
    return session._worker.plan.uid if session._worker else None


def test_honest_submission_answers(open_one):
    session = open_one("_honest")
    assert session.load()["errors"] == []
    assert honest_probe(session) == pytest.approx(HONEST)


def test_sys_exit_at_import_is_a_load_error(open_one):
    session = open_one("exit_at_import")
    errors = session.load()["errors"]
    assert [e["file"] for e in errors] == ["differential_drive.py"]
    assert "SystemExit" in errors[0]["message"]
    with pytest.raises(StudentError, match="differential_drive.py was not loaded"):
        attack(session)


def test_os_exit_at_import_fails_every_call_without_restarting(open_session):
    session = open_session("os_exit_at_import")
    with pytest.raises(WorkerDied, match="imported.*exit status 0"):
        session.load()
    with pytest.raises(WorkerDied, match="imported"):
        honest_probe(session)
    assert session.starts == 1


def test_sys_exit_mid_run_is_a_student_error_with_the_line(open_one):
    session = open_one("exit_mid_run")
    with pytest.raises(StudentError, match=r"sys.exit\(0\)") as caught:
        attack(session)
    assert (caught.value.type_name, caught.value.file) == ("SystemExit", "differential_drive.py")
    source = (REPO / "tests/data/attacks/exit_mid_run/differential_drive.py").read_text().splitlines()
    assert source[caught.value.line - 1].strip() == "sys.exit(0)"
    assert honest_probe(session) == pytest.approx(HONEST)
    assert session.starts == 1


def test_os_exit_mid_run_kills_the_worker_and_the_next_call_restarts(open_session):
    session = open_session("os_exit_mid_run")
    with pytest.raises(WorkerDied, match="exit status 0"):
        attack(session)
    assert honest_probe(session) == pytest.approx(HONEST)
    assert session.starts == 2


def test_killing_the_parent_leaves_the_grader_alive(open_session, mode):
    _needs_own_uid(mode)
    session = open_session("kill_parent")
    result = attack(session)  # were the worker's parent the grader and killable, pytest would be dead
    assert result == pytest.approx(HONEST)
    assert os.getppid() != 1


@pytest.mark.parametrize("kind, name", [("custom", "Boom"), ("interrupt", "KeyboardInterrupt"),
                                        ("generator", "GeneratorExit")])
def test_base_exceptions_become_student_errors(open_one, kind, name):
    session = open_one("base_exception")
    with pytest.raises(StudentError) as caught:
        attack(session, kind=kind)
    assert caught.value.type_name == name and caught.value.file == "differential_drive.py"
    assert honest_probe(session) == pytest.approx(HONEST)


def test_printed_fake_results_are_only_shown_never_parsed(open_one):
    session = open_one("fake_output")
    assert attack(session) == pytest.approx(HONEST)
    output = session.output()
    assert "100/100" in output and '"max_score": 100' in output


def test_fake_answers_on_the_channel_are_caught_by_the_next_id(open_one):
    session = open_one("fake_output")
    value = attack(session, fn="forge_channel")
    # The forged line can only stand in for the student's own return value (the grader validates it)...
    assert value in ([100, 100], pytest.approx(HONEST))
    # ...and the real answer then arrives with a stale id: a protocol violation, the worker is replaced.
    with pytest.raises(WorkerDied, match="does not match"):
        honest_probe(session)
    assert honest_probe(session) == pytest.approx(HONEST)


def test_forged_files_and_detached_writers(open_session, shared_dir, mode):
    _needs_own_uid(mode)
    out = shared_dir / "reports"
    out.mkdir()
    (out / "week1.json").write_text('{"score": 3}')
    canary = shared_dir / "world-writable"
    canary.mkdir()
    canary.chmod(0o777)
    session = open_session("forge_files")
    written = attack(session, targets=[str(out), str(canary)], delay=0.4)
    uid = _uid(session)
    assert not any(w.startswith(str(out)) for w in written)  # the output folder is never writable
    if mode == BWRAP:
        assert written == []                                 # nothing outside is even visible
    session.close()
    time.sleep(0.8)  # the detached writer would have woken up by now
    assert sorted(p.name for p in out.iterdir()) == ["week1.json"]
    assert (out / "week1.json").read_text() == '{"score": 3}'
    assert not [p for p in canary.iterdir() if p.name.startswith("later-")]
    if uid is not None:
        assert not _uid_alive(uid)


def test_monkeypatching_stays_inside_the_worker(open_one):
    session = open_one("monkeypatch")
    value = attack(session)
    # The patched to_json can change only what the worker sends: a row of plain floats no longer goes
    # through it (the honest pair arrives), anything it does go through arrives mangled, as plain JSON the
    # grader's own (unpatched) code refuses.
    honest = [(2 * 0.1 + 0.5 * 0.09925) / (2 * 0.0325), (2 * 0.1 - 0.5 * 0.09925) / (2 * 0.0325)]
    if value != honest:
        with pytest.raises(validate.BadValue, match="a list of 2, expected a number"):
            validate.as_float_list(value, 2, "uni_to_diff returned")
    assert validate.as_float_list(honest, 2, "uni_to_diff returned") == honest
    assert math.sqrt(4.0) == 2.0
    assert not numpy.allclose(1.0, 2.0)
    with pytest.raises(validate.BadValue):
        validate.as_float("100")
    from simiam.course.weeks import spec_for_week

    assert spec_for_week(3) is not None


@pytest.mark.parametrize("kind, message", [("eq", "a Liar object"), ("float_subclass", "a LyingFloat object"),
                                           ("huge_int", "integer too large"), ("deep", "nested more than")])
def test_values_without_json_form_are_refused_by_name(open_one, kind, message):
    session = open_one("evil_objects")
    with pytest.raises(StudentError, match=message) as caught:
        attack(session, kind=kind)
    assert "cannot be sent to the grader" in str(caught.value)


@pytest.mark.parametrize("kind, message", [("nan", "NaN"), ("inf", "infinity")])
def test_nonfinite_values_cross_and_fail_validation(open_one, kind, message):
    session = open_one("evil_objects")
    value = attack(session, kind=kind)
    with pytest.raises(validate.BadValue, match=f"your uni_to_diff returned \\(item 1\\) {message}"):
        validate.as_float_list(value, 2, "your uni_to_diff returned")


def test_huge_floats_are_numbers_far_from_the_answer(open_one):
    session = open_one("evil_objects")
    value = validate.as_float_list(attack(session, kind="huge_float"), 2)
    assert value == [1e308, -1e308] and value != pytest.approx(HONEST)


def test_an_oversized_answer_is_refused_in_words_and_the_worker_goes_on(open_one):
    # the worker holds its answers to the grader's bounds (grader.inside.answer_bounds): a 10 MB string is
    # the student's error, not a broken protocol (a worker that sends it anyway: test_answer_bounds.py)
    session = open_one("evil_objects")
    with pytest.raises(StudentError, match="characters of text, more than the grader takes"):
        attack(session, kind="big_string")
    assert honest_probe(session) == pytest.approx(HONEST) and session.starts == 1


def test_reading_solutions_and_other_files(open_session, mode, shared_dir):
    session = open_session("read_solutions")
    solution = REPO / "solutions" / "week1" / "differential_drive.py"
    grader_file = REPO / "grader" / "reference.py"
    paths = [str(solution), str(grader_file), str(REPO / "pyproject.toml"), "/work/shared/contract.md",
             str(REPO / "tests" / "data" / "attacks" / "_honest" / "quickbot.py")]
    assert solution.exists() and grader_file.exists()
    if mode == BWRAP:
        with pytest.raises(StudentError, match="No such file"):
            attack(session, paths=paths)
        return
    # documented: without bubblewrap it reads what its uid can reach, and the note says which course files
    # that includes wherever the checkout lives (a folder only its owner can open keeps them out: as root,
    # test_private_folders.py lays one out)
    marker = open_marker(shared_dir)
    found = attack(session, paths=[*paths, str(marker)])
    note = session.isolation_note
    assert str(marker) in found and "can read what its user can read" in note
    for name, path in (("solutions/", solution), ("the grader's files", grader_file)):
        assert (str(path) in found) == says_it_reads(note, name), note


def test_network(open_session, mode):
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(1)
    server.settimeout(0.2)
    session = open_session("network")
    try:
        # seccomp refuses the socket in every mode; bubblewrap's empty network namespace is behind it
        with pytest.raises(StudentError, match="PermissionError: .*Permission denied"):
            attack(session, port=server.getsockname()[1])
        with pytest.raises(socket.timeout):
            server.accept()
    finally:
        server.close()
    assert "network" in session.isolation_note


@pytest.mark.parametrize("fn", ["attack", "attack_numpy"])
def test_allocating_gigabytes_is_a_memory_error(open_one, fn):
    session = open_one("allocate")
    with pytest.raises(StudentError, match="Memory"):
        attack(session, fn=fn, gb=4)
    assert honest_probe(session) == pytest.approx(HONEST)


@pytest.mark.skipif(not AS_ROOT, reason="a dedicated uid needs root; as a user the limit counts all of them")
def test_fork_bomb_is_contained_and_killed(open_session):
    limits = Limits(call_seconds=5.0)
    session = open_session("fork_bomb", limits)
    started = attack(session, n=500)
    uid = _uid(session)
    print(f"fork bomb: {started} of 500 forks succeeded under RLIMIT_NPROC={limits.processes}")
    assert started < limits.processes
    session.close()
    assert not _uid_alive(uid)


def test_printing_100_mb_keeps_only_the_first_bytes(open_one):
    session = open_one("flood_output", Limits(call_seconds=10.0, output_bytes=64 * 1024))
    assert attack(session, mb=100) == pytest.approx(HONEST)
    output = session.output()
    assert len(output) < 64 * 1024 + 100
    assert "more bytes of output not kept" in output
    assert session._worker.output.total >= 100 * 2**20


def test_infinite_loop_times_out_and_the_worker_is_replaced(open_session):
    session = open_session("infinite_loop")  # the short limit only on the call that hangs
    began = time.monotonic()
    with pytest.raises(StudentTimeout, match="no answer within 1 s, the time limit per call"):
        attack(session, timeout=1.0)
    print(f"infinite loop stopped after {time.monotonic() - began:.2f} s (limit 1 s)")
    assert honest_probe(session) == pytest.approx(HONEST)
    assert session.starts == 2


def test_sleeping_past_the_limit_until_the_budget_is_spent(open_one):
    """Two timed-out calls of 1 s spend the 2 s in all, whatever the load: then every call, honest ones too,
    is refused at once. (With 0.4 s calls in 1 s, the restarted worker's loading had to fit in the last
    0.1 s or so, and the third call's error depended on how fast that was.)"""
    limits = Limits(call_seconds=1.0, total_seconds=2.0)
    session = open_one("sleep", limits)
    with pytest.raises(StudentTimeout):
        attack(session)
    with pytest.raises(StudentTimeout):
        attack(session)  # the fresh worker loads within the ~1 s left, then this call spends the rest
    with pytest.raises(StudentTimeout, match="used up its total time"):
        attack(session)
    with pytest.raises(StudentTimeout, match="used up its total time"):
        honest_probe(session)
    assert session.seconds_used < limits.total_seconds + limits.call_seconds  # not a third timed-out call


def test_robot_limits_changed_in_the_worker_stay_there(open_one):
    from simiam.course.weeks import spec_for_week

    before = spec_for_week(3).max_vel
    session = open_one("robot_limits")
    attack(session)
    assert spec_for_week(3).max_vel == before < 1e9


def test_large_files_hit_the_file_size_limit_and_are_removed(open_session, mode):
    _needs_own_uid(mode)
    path = f"/tmp/simiam-fill-{uuid.uuid4().hex}"
    session = open_session("disk_fill")
    try:
        with pytest.raises(StudentError, match="File too large|No space left"):
            attack(session, path=path)
        session.close()
        assert not os.path.exists(path)  # under bwrap it never was there; without, it is swept at close
    finally:
        if os.path.exists(path):
            os.unlink(path)


def test_the_worker_sees_no_secrets_and_no_repository(open_session, mode, monkeypatch):
    monkeypatch.setenv("SIMIAM_GRADER_SECRET", "s3cret")
    session = open_session("snoop")
    paths = [str(REPO / "solutions"), str(REPO / "simiam"), "/work/shared", str(REPO / "tests" / "data"),
             str(REPO / "grader" / "hidden"), str(REPO / "grader" / "checks"), str(REPO / "reports")]
    seen = attack(session, paths=paths)
    assert "SIMIAM_GRADER_SECRET" not in seen["environ"] and "s3cret" not in seen["cmdline"]
    # the numeric environment simiam.numerics pins (kernel, threads, SIMD level) and nothing else; TMPDIR is
    # a plain subprocess's private folder (issue 30 item 3)
    assert set(seen["environ"]) <= {"PATH", "HOME", "LANG", "TMPDIR", *numerics.PINNED_VARIABLES,
                                     numerics.OVERRIDE}
    if AS_ROOT:
        assert seen["uid"] != 0
    if mode == BWRAP:
        # simiam/ too: the worker imports its own copy of the student-facing modules (grader.sandbox.exposed)
        assert [seen["exists"][p] for p in paths] == [False, False, False, False, False, False, False]
        assert all(Path(p).exists() for p in paths[:2] + paths[3:6])  # they are there, outside
        assert seen["hostname"] == "sandbox" and max(seen["pids"]) < 10
        assert seen["cwd"] == "/submission"
        assert seen["interfaces"] == ["lo"]  # the network namespace, independent of the seccomp filter
    assert sys.executable  # the grader itself is untouched


def test_probes_outside_the_allow_list_are_refused(open_one):
    session = open_one("_honest")
    with pytest.raises(StudentError, match="no probe named 'not_allowed'"):
        session.call("probe", name="not_allowed", args={})


def test_cpu_time_is_capped_by_the_kernel(open_one):
    # The wall limit is generous here, so only RLIMIT_CPU can stop the loop early: one CPU second can take
    # several seconds of wall time when the worker shares two busy cores, and 60 s is spent only on failure.
    session = open_one("infinite_loop", Limits(call_seconds=60.0, cpu_seconds=1))
    began = time.monotonic()
    with pytest.raises(WorkerDied, match="CPU time limit"):
        attack(session)
    print(f"CPU limit 1 s: worker ended after {time.monotonic() - began:.2f} s wall")


@pytest.mark.skipif(not AS_ROOT, reason="per-session groups need root")
def test_a_concurrent_submission_is_not_readable(open_session):
    other = open_session("_honest")
    other.load()
    target = str(other._work.path / "differential_drive.py")
    assert Path(target).exists()
    session = open_session("read_solutions")
    with pytest.raises(StudentError, match="Permission denied|No such file"):
        attack(session, paths=[target])


@pytest.mark.parametrize("kind, error, message", [
    ("close", WorkerDied, "closed the grader's channel|exit status"),
    ("ignore_term", StudentTimeout, "no answer within"),
])
def test_channel_and_signal_abuse(open_one, kind, error, message):
    session = open_one("channel_abuse")  # the short limit only on the abusive call, not on the fresh worker's
    with pytest.raises(error, match=message):
        attack(session, kind=kind, timeout=0.7)
    assert honest_probe(session) == pytest.approx(HONEST)  # a fresh worker answers
    assert session.starts == 2


@pytest.mark.skipif(seccomp.program() is None, reason="no seccomp filter for this machine")
def test_a_worker_cannot_stop_itself(open_one):
    """SIGSTOP (or SIGTSTP...) sent to itself is refused by the worker's filter: a stopped worker looks like
    a machine that paused it, which is never charged (grader.sandbox.worker_clock). Before, the stop ran
    into the per-call timeout; now the call raises at once and the worker goes on."""
    session = open_one("channel_abuse")
    with pytest.raises(StudentError, match="Operation not permitted"):
        attack(session, kind="stop", timeout=0.7)
    assert honest_probe(session) == pytest.approx(HONEST) and session.starts == 1


def _sysv_keys() -> set[tuple[str, int]]:
    """(kind, key) of every System V IPC object on this machine's IPC namespace."""
    found = set()
    for kind in ("shm", "msg", "sem"):
        try:
            lines = Path(f"/proc/sysvipc/{kind}").read_text().splitlines()[1:]
        except OSError:
            continue
        found.update((kind, int(line.split()[0])) for line in lines if line.strip())
    return found


def _remove_sysv(kind_keys: list) -> None:
    from grader.sandbox.leftovers import _IPC_RMID

    libc = ctypes.CDLL(None, use_errno=True)
    for kind, key in kind_keys:
        ident = (libc.shmget if kind == "shm" else libc.msgget)(key, 0, *([0] if kind == "shm" else []))
        if ident >= 0:
            (libc.shmctl if kind == "shm" else libc.msgctl)(ident, _IPC_RMID, None)


@pytest.mark.parametrize("sweep", [True, False], ids=["swept", "wrong-not-swept"])
def test_ipc_objects_and_shared_files_do_not_outlive_the_worker(open_session, mode, monkeypatch, sweep):
    """Issue 10 item 9. Under bubblewrap the sandbox's own IPC namespace and /tmp die with it; in
    subprocess mode (root, the worker's own uid) the grader removes by uid what it left. The wrong version
    (no IPC removal, as before) leaves the shared memory for the next student."""
    from grader.sandbox import runner as sandbox_runner

    if not sweep:
        if mode != SUBPROCESS or not AS_ROOT:
            pytest.skip("the wrong version only shows in subprocess mode with a dedicated uid")
        monkeypatch.setattr(sandbox_runner, "remove_ipc_of", lambda uid: [])
    key = 0x51570000 + (os.getpid() % 0xFFFF)
    session = open_session("ipc_leftovers")
    left = attack(session, key=key)
    session.close()
    created = {(kind, k) for kind, k in left["sysv"]}
    try:
        if mode == BWRAP:
            assert not created & _sysv_keys()            # never in the machine's namespace at all
        elif not AS_ROOT:
            pytest.skip("without a dedicated uid subprocess mode cannot tell leftovers apart (documented)")
        else:
            assert created, "the attack could not create System V objects: the test would prove nothing"
            assert bool(created & _sysv_keys()) != sweep
        if sweep:
            assert not [p for p in left["files"] if os.path.exists(p)]
    finally:
        _remove_sysv(sorted(created & _sysv_keys()))
        for path in left["files"]:
            if os.path.exists(path):
                os.unlink(path)
