"""Issue 30 item 3: nothing one student's worker writes outlives it for a student graded later. Under
bubblewrap the worker's /tmp is its own and the rest of the system is read-only; in plain subprocess mode
as root the worker gets a private HOME and TMPDIR, and every folder its uid could write is swept after it
(grader.sandbox.leftovers: found by walking the writable mounts, not a fixed list).

The attack (tests/data/attacks/note_for_next/) writes a note into every folder it can write, /run/lock
included, and a second student's worker then looks for the notes. The sweep as it was (four listed folders,
kept in sandbox_wrong/fixed_sweep.py) leaves the note in /run/lock, which the next student reads.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from sandbox_helpers import AS_ROOT, LIMITS, PROBES, attack, make_submission
from sandbox_wrong import fixed_sweep

from grader.sandbox import leftovers
from grader.sandbox.isolation import BWRAP, SUBPROCESS
from grader.sandbox.session import StudentSession

SHARED_LOCKS = Path("/run/lock")   # open to all on Debian and Ubuntu (1777), and outside the old list


def _session(folder: Path, mode: str) -> StudentSession:
    folder.mkdir()
    folder.chmod(0o711)
    return StudentSession(1, make_submission(folder, "note_for_next"), LIMITS, sandbox=mode,
                          probes="sandbox_probes", extra_paths=(str(PROBES),))


@pytest.mark.parametrize("sweep", ["found", "wrong-fixed-list"])
def test_a_note_left_for_the_next_student_is_gone(shared_dir, mode, monkeypatch, sweep):
    if mode == SUBPROCESS and not AS_ROOT:
        pytest.skip("documented: without root the worker keeps the grader's user, and nothing is swept")
    if sweep != "found":
        if mode != SUBPROCESS:
            pytest.skip("the wrong sweep only shows in subprocess mode with a dedicated uid")
        monkeypatch.setattr(leftovers, "writable_folders", fixed_sweep.writable_folders)
    with _session(shared_dir / "first", mode) as first:
        left = attack(first, fn="leave")
    try:
        assert left, "the attack could write nowhere: the test would prove nothing"
        if mode == SUBPROCESS and os.access(SHARED_LOCKS, os.W_OK):
            assert any(p.startswith(f"{SHARED_LOCKS}/") for p in left), left
        with _session(shared_dir / "second", mode) as second:
            found = attack(second, fn="read", paths=left)
        assert (found == {}) == (sweep == "found"), f"the next student read: {sorted(found)}"
        if mode == BWRAP:
            assert not [p for p in left if os.path.exists(p)], "a note outside the sandbox"
    finally:
        for path in left:
            if os.path.lexists(path) and os.stat(path, follow_symlinks=False).st_uid != 0:
                os.unlink(path)


@pytest.mark.skipif(not AS_ROOT, reason="a dedicated uid, and so a private folder, needs root")
def test_a_plain_subprocess_worker_has_a_private_home_and_temporary_folder(shared_dir):
    with _session(shared_dir / "first", SUBPROCESS) as first:
        left = attack(first, fn="leave")
        private = [p for p in left if "/simiam-work-" in p and "/private/" in p]
        assert private, left                       # TMPDIR and HOME: the worker's own folder
        assert oct(os.stat(Path(private[0]).parent).st_mode & 0o777) == "0o700"
    assert not [p for p in private if os.path.exists(p)]   # removed with the work copy


def test_the_walk_finds_the_folders_open_to_all_and_skips_the_rest(tmp_path):
    top = tmp_path / "top"
    for name, mode in (("open", 0o1777), ("closed", 0o700), ("closed/open", 0o1777), ("readable", 0o755),
                       ("readable/open", 0o777), ("readable/no_x", 0o776)):
        (top / name).mkdir(parents=True)
        (top / name).chmod(mode)
    top.chmod(0o755)
    found, finished = leftovers.walk_writable([str(top)])
    assert finished
    assert sorted(Path(p).relative_to(top).as_posix() for p in found) == ["open", "readable/open"]
    assert leftovers.walk_writable([str(top)], seconds=-1.0) == ([], False)   # past its bound: unfinished


def test_the_mounts_walked_are_the_writable_ones(tmp_path):
    info = tmp_path / "mountinfo"
    info.write_text(
        "22 1 8:1 / / rw,relatime shared:1 - ext4 /dev/sda1 rw\n"
        "23 22 0:5 / /proc rw,nosuid - proc proc rw\n"
        "24 22 0:6 / /usr ro,relatime - ext4 /dev/sda2 ro\n"
        "25 22 0:7 / /run/lock rw,nosuid - tmpfs tmpfs rw\n"
        "26 22 0:8 / /mnt/a\\040b rw - ext4 /dev/sdb rw\n"
        "27 22 0:9 / /sys/fs/cgroup rw - cgroup2 cgroup2 rw\n")
    assert leftovers.writable_mounts(str(info)) == ["/", "/run/lock", "/mnt/a b"]
