"""Student zips are opened safely; every hostile case is refused with a reason, and is hostile enough
that a naive reader (tests/data/batch/wrong_batch.py) would have let it through."""

from __future__ import annotations

import zipfile
from pathlib import Path

import pytest
from batch_helpers import make_zip

from grader.batch.zips import Limits, SubmissionRefused, read_zip

NOISE = "".join(f"{(i * 7919) % 65521:05d}" for i in range(380))   # 1900 bytes that barely compress
SMALL = Limits(max_files=5, max_file_bytes=2000, max_total_bytes=3000, max_ratio=50, ratio_floor_bytes=1000)


def hostile(tmp: Path) -> dict[str, tuple[Path, str]]:
    """name -> (zip, words the refusal must contain)."""
    return {
        "absolute": (make_zip(tmp / "abs.zip", {"/etc/evil.py": "x"}), "absolute"),
        "dotdot": (make_zip(tmp / "dd.zip", {"week3/../../evil.py": "x"}), "outside"),
        "windows": (make_zip(tmp / "win.zip", {"C:\\evil.py": "x"}), "absolute"),
        "symlink": (make_zip(tmp / "ln.zip", {"a.py": "x"}, symlinks={"go_to_goal.py": "/etc/passwd"}),
                    "symlink"),
        "per_file": (make_zip(tmp / "big.zip", {"a.py": "x" * 2500}), "limit per file"),
        "total": (make_zip(tmp / "tot.zip", {"a.py": NOISE, "b.py": NOISE[::-1]}), "size limit"),
        "count": (make_zip(tmp / "n.zip", {f"f{i}.py": "x" for i in range(6)}), "more than 5 files"),
        "bomb": (make_zip(tmp / "bomb.zip", {"a.py": "\0" * 1900}), "zip bomb"),
        "duplicate": (make_zip(tmp / "dup.zip", {"a.py": "1", "./a.py": "2"}), "two entries"),
    }


@pytest.mark.parametrize("case", ["absolute", "dotdot", "windows", "symlink", "per_file", "total", "count",
                                  "bomb", "duplicate"])
def test_hostile_zip_is_refused_and_naive_reader_is_not(tmp_path: Path, case: str, wrong) -> None:
    path, words = hostile(tmp_path)[case]
    with pytest.raises(SubmissionRefused, match=words):
        read_zip(path, SMALL)
    naive = wrong.naive_read_zip(path)       # the case really is hostile: a naive reader takes it
    assert naive


def test_not_a_zip_and_truncated_zip(tmp_path: Path) -> None:
    (tmp_path / "a.zip").write_bytes(b"PK\x03\x04 not really")
    with pytest.raises(SubmissionRefused, match="not a readable zip"):
        read_zip(tmp_path / "a.zip")
    good = make_zip(tmp_path / "b.zip", {"go_to_goal.py": "x = 1\n" * 200})
    (tmp_path / "c.zip").write_bytes(good.read_bytes()[:-40])
    with pytest.raises(SubmissionRefused):
        read_zip(tmp_path / "c.zip")


def test_encrypted_entry_is_refused(tmp_path: Path) -> None:
    path = make_zip(tmp_path / "e.zip", {"a.py": "x"})
    data = bytearray(path.read_bytes())
    # set the "encrypted" flag in the local header and the central directory entry
    data[6] |= 1
    central = data.find(b"PK\x01\x02")
    data[central + 8] |= 1
    path.write_bytes(bytes(data))
    with pytest.raises(SubmissionRefused, match="encrypted"):
        read_zip(path)


def test_junk_is_skipped_and_files_are_read(tmp_path: Path) -> None:
    path = make_zip(tmp_path / "ok.zip", {"week3/go_to_goal.py": "K = 1\n",
                                          "__MACOSX/week3/._go_to_goal.py": "j",
                                          "week3/.DS_Store": "j", "week3/__pycache__/x.pyc": "j"})
    assert read_zip(path) == {"week3/go_to_goal.py": b"K = 1\n"}


def test_a_deflate_bomb_is_refused_by_ratio_with_default_limits(tmp_path: Path) -> None:
    path = tmp_path / "bomb.zip"
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("go_to_goal.py", b"\0" * (4 * 1024 * 1024))
    assert path.stat().st_size < 20_000
    with pytest.raises(SubmissionRefused, match="zip bomb"):
        read_zip(path)
