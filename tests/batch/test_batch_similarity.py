"""Similarity on what a batch takes: a Canvas "Download Submissions" zip as downloaded (independent
week-3 solutions, a planted copy with names, comments and spacing changed, a held and an unreadable
student), through ``grade similarity weekN SOURCE`` and ``grade weekN --batch SOURCE --similarity``;
the page's numbers are checked against the comparer run on the same students as a class folder, and
each kept wrong version (tests/data/similarity/wrong_platform.py) is caught."""

from __future__ import annotations

import html
import importlib
import importlib.util
import io
import json
import re
import shutil
from html.parser import HTMLParser
from pathlib import Path

import pytest
from batch_helpers import make_zip

from grader.batch.intake import IntakeOptions
from grader.batch.runner import BatchOptions, run_batch
from grader.cli import main as grade_main
from grader.similarity.command import THRESHOLD, after_batch, read_class
from grader.similarity.compare import compare
from grader.similarity.students import read_source
from grader.similarity.submitted import handout_blocks

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data" / "similarity"
FAKE = "batch_fake_grader:fake_grade"
# Canvas user id -> (Canvas's name, the roster's name, whose files: tests/data/similarity/week3/...)
HOSTILE = "Roe, Ann <img src=x onerror=alert(1)>" + "y" * 80      # a roster cell: cut and escaped
STUDENTS = {
    "101": ("alvesana", "Alves, Ana", "independent/ana"),
    "102": ("bakerben", "Baker, Ben", "independent/ben"),
    "103": ("chenchen", "Chen, Chen", "independent/chen"),
    "104": ("roeann_LATE", HOSTILE, "planted/ana_renamed"),     # ana's work, renamed and re-spaced
    "105": ("solsam", "Sol, Sam", None),                        # the reference solution
}
PLANTED = ("101", "104")
HELD, BROKEN = "112", "113"


def canvas_zip(path: Path) -> Path:
    """The zip as Canvas names its entries (<name>[_LATE]_<user id>_<attachment id>_<file>): each
    student's five week-3 files, a student with a re-upload Canvas renamed (held: which file is the
    submission cannot be told), one whose uploaded zip is not a zip, and a stray entry."""
    entries: dict[str, bytes | str] = {}
    attachment = 9000
    for uid, (name, _roster, own) in STUDENTS.items():
        for f in sorted((ROOT / "solutions" / "week3").glob("*.py")):
            attachment += 1
            mine = DATA / "week3" / own / f.name if own else f
            entries[f"{name}_{uid}_{attachment}_{f.name}"] = (mine if mine.is_file() else f).read_bytes()
    gtg = (ROOT / "solutions" / "week3" / "go_to_goal.py").read_bytes()
    entries[f"twicetom_{HELD}_9101_go_to_goal.py"] = gtg
    entries[f"twicetom_{HELD}_9102_go_to_goal-1.py"] = gtg
    entries[f"brokenzip_{BROKEN}_9103_week3.zip"] = b"this is not a zip"
    entries["notes from the TA.txt"] = "not a submission"
    return make_zip(path, entries)


def roster(path: Path) -> Path:
    """A Canvas gradebook export as the roster."""
    rows = [f'"{r}",{uid},S{uid},login{uid},A' for uid, (_n, r, _o) in STUDENTS.items()]
    rows += [f'"Twice, Tom",{HELD},S{HELD},t,A', f'"Broken, Zip",{BROKEN},S{BROKEN},b,A']
    path.write_text("Student,ID,SIS User ID,SIS Login ID,Section\n    Points Possible,,,,\n"
                    + "\n".join(rows) + "\n")
    return path


def expected_scores(tmp_path: Path) -> dict[frozenset, float]:
    """The comparer on the same five students laid out as a class folder (one folder per id)."""
    folder = tmp_path / "as-folders"
    for uid, (_n, _r, own) in STUDENTS.items():
        shutil.copytree(ROOT / "solutions" / "week3", folder / uid,
                        ignore=shutil.ignore_patterns("__pycache__", "README.md"))
        for f in (DATA / "week3" / own).iterdir() if own else ():
            shutil.copy(f, folder / uid / f.name)
    codes = read_class(folder, 3).codes
    return {frozenset((p.a.id, p.b.id)): p.score for p in compare(codes, handout_blocks(3))}


class _Page(HTMLParser):
    """The ranking table's rows and the paragraph of scores below the threshold, as text."""

    def __init__(self) -> None:
        super().__init__()
        self.rows: list[list[str]] = []
        self.tables = 0
        self.paragraphs: list[str] = []
        self.where: str | None = None

    def handle_starttag(self, tag: str, attrs: list) -> None:
        if tag == "table":
            self.tables += 1
        elif tag == "tr" and self.tables == 1:
            self.rows.append([])
        elif tag in ("td", "th") and self.tables == 1 and self.rows:
            self.rows[-1].append("")
            self.where = "cell"
        elif tag == "p":
            self.paragraphs.append("")
            self.where = "p"

    def handle_endtag(self, tag: str) -> None:
        if tag in ("td", "th", "p", "table"):
            self.where = None

    def handle_data(self, data: str) -> None:
        if self.where == "cell":
            self.rows[-1][-1] += data
        elif self.where == "p":
            self.paragraphs[-1] += data


def label(uid: str, name: str) -> str:
    """How the page names a student: id and name, the name cut to 60 characters."""
    return f"{uid} ({name if len(name) <= 60 else name[:59] + '…'})"


def page_problems(out: Path, names: dict[str, str], scores: dict[frozenset, float]) -> list[str]:
    """What is wrong with out/similarity.html and similarity.json: the planted pair first with its score
    and only it at or above the threshold, the best pairs below it with their scores, each student named
    as their identity names them, the held and the unreadable student listed as not compared."""
    page_file = out / "similarity.html"
    if not page_file.is_file():
        return [f"no {page_file}"]
    text = page_file.read_text()
    problems = []
    if "<img" in text or "onerror=alert(1)&gt;" + "y" * 80 in text:
        problems.append("a name reached the page unescaped or uncut")
    page = _Page()
    page.feed(text)
    rows = [[" ".join(c.split()) for c in r[:4]] for r in page.rows[1:]]
    a, b = PLANTED
    want = [["1", label(a, names[a]), label(b, names[b]), f"{int(scores[frozenset(PLANTED)] * 100)} %"]]
    if rows != want:
        problems.append(f"ranking table: {rows}, expected {want}")
    below = next((p for p in page.paragraphs if p.startswith("Highest scores below")), "")
    shown = re.findall(r"(\d+) \((.*?)\) and (\d+) \((.*?)\) (\d+) %", below)
    others = sorted((s for p, s in scores.items() if p != frozenset(PLANTED)), reverse=True)
    if [int(s) for *_, s in shown] != [int(s * 100) for s in others[:5]]:
        problems.append(f"scores below the threshold: {below!r}, expected {others[:5]}")
    if any(s >= THRESHOLD for s in others) or any(int(s) >= THRESHOLD * 100 for *_, s in shown):
        problems.append(f"an independent pair at or above the threshold: {others}")
    for x, xn, y, yn, _s in shown:
        if (xn, yn) != (label(x, names[x])[len(x) + 2:-1], label(y, names[y])[len(y) + 2:-1]):
            problems.append(f"below the threshold, {x} and {y} are named {xn!r} and {yn!r}")
    for uid, reason in ((HELD, "held (yours to sort out"), (BROKEN, "zip")):
        if not re.search(rf"<li>{uid} \([^)]*\): [^<]*{re.escape(reason)}", text):
            problems.append(f"{uid} is not listed as not compared with why ({reason!r})")
    report = json.loads((out / "similarity.json").read_text())
    first = report["pairs"][0] if report["pairs"] else {}
    got = (first.get("a"), first.get("b"), first.get("a_name"), first.get("b_name"), first.get("score"))
    if got != (a, b, names[a], names[b], scores[frozenset(PLANTED)]) or len(report["pairs"]) != 1:
        problems.append(f"similarity.json's pairs: {report['pairs']}")
    if sorted(report["not_compared"]) != [HELD, BROKEN] or report["compared"] != len(STUDENTS):
        problems.append(f"similarity.json: compared {report['compared']}, not {report['not_compared']}")
    return problems


@pytest.fixture(scope="module")
def download(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path, dict[frozenset, float]]:
    """The Canvas zip, its roster and the scores the comparer gives the same students as folders."""
    folder = tmp_path_factory.mktemp("canvas")
    return canvas_zip(folder / "CS101-HW3_submissions.zip"), roster(folder / "roster.csv"), \
        expected_scores(folder)


def _wrong(name: str) -> dict:
    spec = importlib.util.spec_from_file_location("wrong_platform", DATA / "wrong_platform.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return getattr(module, name)


def _similarity(zip_path: Path, out: Path, roster_path: Path | None) -> int:
    more = ["--roster", str(roster_path)] if roster_path else []
    return grade_main(["similarity", "week3", str(zip_path), "--out", str(out), *more])


def test_the_zip_as_downloaded(download: tuple, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    zip_path, roster_path, scores = download
    assert scores[frozenset(PLANTED)] == 1.0, scores        # the copy, renamed and re-spaced: all of it
    canvas = {uid: n.removesuffix("_LATE") for uid, (n, _r, _o) in STUDENTS.items()}
    assert _similarity(zip_path, tmp_path / "platform", None) == 0
    printed = capsys.readouterr().out
    assert printed.startswith('reading Canvas "Download Submissions": CS101-HW3_submissions.zip, 7 students\n'
                              "1 pair scores 60% or more\n"
                              "    1. 100%  101 (alvesana)  104 (roeann)  ("), printed
    assert page_problems(tmp_path / "platform", canvas, scores) == []
    rostered = {uid: r for uid, (_n, r, _o) in STUDENTS.items()}
    assert _similarity(zip_path, tmp_path / "roster", roster_path) == 0
    assert page_problems(tmp_path / "roster", rostered, scores) == []
    page = (tmp_path / "roster" / "similarity.html").read_text()
    unplaced = "1 entry of the\ndownload could not be placed with any student (not compared): notes from"
    assert unplaced + " the TA.txt." in page
    cut = label("104", HOSTILE)
    assert cut.endswith("y…)") and len(cut) == len("104 ()") + 60 and html.escape(cut) in page, cut


@pytest.mark.parametrize("name", sorted(_wrong("WRONG")))
def test_wrong_version_is_caught(download: tuple, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                 name: str) -> None:
    zip_path, roster_path, scores = download
    for module, attribute, replacement in _wrong("WRONG")[name]:
        monkeypatch.setattr(importlib.import_module(module), attribute, replacement)
    rostered = {uid: r for uid, (_n, r, _o) in STUDENTS.items()}
    try:
        code = _similarity(zip_path, tmp_path / "o", roster_path)
    except Exception as exc:  # noqa: BLE001 - a wrong version may break outright: that is caught too
        code = f"raised {exc!r}"
    problems = page_problems(tmp_path / "o", rostered, scores) if code == 0 else [f"exit {code}"]
    assert problems, f"{name}: not caught"


def _batch(zip_path: Path, roster_path: Path, out: Path) -> tuple[dict, str]:
    stream = io.StringIO()
    report = run_batch(BatchOptions(week=3, batch_dir=zip_path, out=out, seed=3, jobs=1, similarity=True,
                                    intake=IntakeOptions(roster=roster_path)), grade_fn=FAKE, stream=stream)
    return report, stream.getvalue()


def test_batch_option(download: tuple, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    zip_path, roster_path, scores = download
    report, said = _batch(zip_path, roster_path, tmp_path / "graded")
    out = tmp_path / "graded"
    assert (report["counts"]["graded"], report["counts"]["invalid"], report["counts"]["held"]) == (5, 1, 1)
    rostered = {uid: r for uid, (_n, r, _o) in STUDENTS.items()}
    assert page_problems(out, rostered, scores) == []
    top = f"similarity of the students' code blocks:\n1 pair scores 60% or more\n    1. 100%  " \
          f"101 (Alves, Ana)  {label('104', HOSTILE)}  ("
    assert top in said, said
    assert said.index(top) < said.index("week 3: 5 graded"), "the pairs are printed before the last line"
    # the same numbers as grade similarity on the same download and roster
    assert _similarity(zip_path, tmp_path / "alone", roster_path) == 0
    alone = json.loads((tmp_path / "alone" / "similarity.json").read_text())
    assert json.loads((out / "similarity.json").read_text()) == alone
    assert '<a href="similarity.html">Similar code blocks</a>' in (out / "summary.html").read_text()
    for module, attribute, replacement in _wrong("WRONG_BATCH")["summary without the link"]:
        monkeypatch.setattr(importlib.import_module(module), attribute, replacement)
    _batch(zip_path, roster_path, tmp_path / "wrong")
    assert '<a href="similarity.html">' not in (tmp_path / "wrong" / "summary.html").read_text(), \
        "the wrong summary is not caught"


def test_the_batch_hook_writes_no_link_and_never_stops_the_batch(download: tuple, tmp_path: Path) -> None:
    """--similarity's call: a link planted at similarity.json is refused, never written through; a page
    that cannot be written is said, and the call returns (the batch then writes its class files)."""
    zip_path, roster_path, _scores = download
    klass = read_source(zip_path, roster=roster_path)
    out = tmp_path / "graded"
    out.mkdir()
    outside = tmp_path / "outside.json"
    outside.write_text("mine\n")
    (out / "similarity.json").symlink_to(outside)
    said = io.StringIO()
    after_batch(klass, 3, out, said)
    assert outside.read_text() == "mine\n", "written through the link"
    last = said.getvalue().splitlines()[-1]
    assert last.startswith("similarity: not written: ") and "link" in last, said.getvalue()
    blocked = tmp_path / "blocked"
    (blocked / "similarity.html").mkdir(parents=True)       # cannot be replaced by a file
    said = io.StringIO()
    after_batch(klass, 3, blocked, said)
    assert said.getvalue().splitlines()[-1].startswith("similarity: not written: "), said.getvalue()
    failing = "grader.similarity.command.compare_class"
    with pytest.MonkeyPatch.context() as patch:     # whatever breaks in it, the call returns
        patch.setattr(failing, lambda *a, **k: 1 / 0)
        said = io.StringIO()
        after_batch(klass, 3, blocked, said)
    assert said.getvalue().splitlines()[-1] == "similarity: not written: ZeroDivisionError: division by zero"
