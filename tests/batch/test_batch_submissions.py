"""The class folder: discovery, folders read with the zip limits, links that leave the folder refused,
the submission root found inside nested zips, and a content hash that ignores packaging."""

from __future__ import annotations

import os
from pathlib import Path

from batch_helpers import make_zip

from grader.batch.submissions import Student, content_hash, discover, find_root, read_submission
from grader.batch.zips import Limits


def test_discover_lists_folders_and_zips_by_id(tmp_path: Path) -> None:
    (tmp_path / "alice").mkdir()
    make_zip(tmp_path / "bob.ZIP", {"a.py": "x"})
    (tmp_path / "notes.txt").write_text("not a submission")
    (tmp_path / ".hidden").mkdir()
    (tmp_path / "carol").mkdir()
    make_zip(tmp_path / "carol.zip", {"a.py": "x"})
    found = {s.id: s.kind for s in discover(tmp_path)}
    assert found == {"alice": "folder", "bob": "zip", "carol": "clash"}
    clash = read_submission(next(s for s in discover(tmp_path) if s.id == "carol"))
    # made on the instructor's side: held for them, never the student's "invalid"
    assert clash.refused is None and clash.held and "both a folder and a zip" in clash.held
    os.symlink(tmp_path / "alice", tmp_path / "dave")            # a linked student is reported, not lost
    os.symlink(tmp_path / "bob.ZIP", tmp_path / "erin.zip")
    found = {s.id: s for s in discover(tmp_path)}
    assert found["dave"].kind == found["erin"].kind == "link"
    for sid in ("dave", "erin"):
        linked = read_submission(found[sid])
        assert linked.refused and "is a link; links are not followed" in linked.refused and not linked.files


def test_folder_link_outside_is_refused_inside_is_read(tmp_path: Path) -> None:
    secret = tmp_path / "solutions.py"
    secret.write_text("ANSWER = 42\n")
    sub = tmp_path / "class" / "mallory"
    sub.mkdir(parents=True)
    (sub / "go_to_goal.py").write_text("K = 1\n")
    os.symlink(sub / "go_to_goal.py", sub / "alias.py")
    ok = read_submission(Student("mallory", sub, "folder"))
    assert ok.refused is None and ok.files["alias.py"] == b"K = 1\n"
    os.symlink(secret, sub / "quickbot.py")
    bad = read_submission(Student("mallory", sub, "folder"))
    assert bad.refused and "outside the submission" in bad.refused and not bad.files
    (sub / "quickbot.py").unlink()
    os.symlink(tmp_path, sub / "up")                 # a directory link out
    bad = read_submission(Student("mallory", sub, "folder"))
    assert bad.refused and "up" in bad.refused


def test_folder_limits_apply(tmp_path: Path) -> None:
    sub = tmp_path / "big"
    sub.mkdir()
    (sub / "a.py").write_text("x" * 3000)
    refused = read_submission(Student("big", sub, "folder"), Limits(max_file_bytes=2000))
    assert refused.refused and "a.py is 3000 bytes" in refused.refused


def test_nested_single_folder_and_whole_course_zip(tmp_path: Path) -> None:
    nested = make_zip(tmp_path / "alice.zip", {"week3/go_to_goal.py": "K = 1\n", "week3/quickbot.py": "q\n"})
    sub = read_submission(Student("alice", nested, "zip"))
    assert sub.root == "week3" and set(sub.files) == {"go_to_goal.py", "quickbot.py"}
    course = make_zip(tmp_path / "bob.zip", {"simiam/README.md": "r",
                                             "simiam/assignments/week2/quickbot.py": "2",
                                             "simiam/assignments/week3/quickbot.py": "3",
                                             "simiam/assignments/week3/go_to_goal.py": "3"})
    sub = read_submission(Student("bob", course, "zip"))
    assert sub.root == "simiam/assignments/week3" and sub.files["quickbot.py"] == b"3"
    # the whole assignments folder: week 4 has the most files, but a week-3 batch grades week3/
    weeks = {f"assignments/week{n}/{name}": str(n) for n in (2, 3, 4)
             for name in ("quickbot.py", "go_to_goal.py", "avoid_obstacles.py")[:n - 1]}
    everything = make_zip(tmp_path / "carl.zip", weeks)
    assert read_submission(Student("carl", everything, "zip")).root == "assignments/week4"   # no week given
    sub = read_submission(Student("carl", everything, "zip"), week=3)
    assert sub.root == "assignments/week3" and sub.files == {"quickbot.py": b"3", "go_to_goal.py": b"3"}


def test_find_root_keeps_top_level_files() -> None:
    assert find_root({"go_to_goal.py": b"1", "extra/x.py": b"2"}) == ("", {"go_to_goal.py": b"1",
                                                                           "extra/x.py": b"2"})


def test_hash_ignores_packaging_but_not_content(tmp_path: Path) -> None:
    folder = tmp_path / "alice"
    folder.mkdir()
    (folder / "go_to_goal.py").write_text("K = 1\n")
    zipped = make_zip(tmp_path / "alice.zip", {"alice/go_to_goal.py": "K = 1\n"})
    a = read_submission(Student("alice", folder, "folder"))
    b = read_submission(Student("alice", zipped, "zip"))
    assert a.sha256 == b.sha256
    assert content_hash({"go_to_goal.py": b"K = 2\n"}) != a.sha256
    assert content_hash({"go_to_goal2.py": b"K = 1\n"}) != a.sha256


def test_a_fifo_is_refused_not_read(tmp_path: Path) -> None:
    sub = tmp_path / "pipe"
    sub.mkdir()
    os.mkfifo(sub / "go_to_goal.py")         # reading it would block the batch forever
    refused = read_submission(Student("pipe", sub, "folder"))
    assert refused.refused and "not a regular file" in refused.refused


def test_an_unreadable_submission_is_refused_not_raised(tmp_path: Path) -> None:
    refused = read_submission(Student("gone", tmp_path / "gone", "folder"))
    assert refused.refused is not None and refused.files == {}
