"""The commands the documentation gives, extracted as a reader would copy them, and how the docs test runs
them (tests/docs/test_documented_commands.py).

A command is a line of a ```bash block in README.md, docs/*.md or assignments/week*/README.md (a trailing
`# comment` dropped, a line ending in `\\` joined to the next); `a && b` runs as written, minus the steps
that install (see SKIPPED). The handout READMEs speak to a student: their commands run in a student's
course folder (one handout folder per week, nothing else); the others run in a copy of the checkout, with
a `submissions/` folder for the batch commands. Each block runs line after line in one folder, so a `cd`
carries over to the lines after it, as in a terminal.

SKIPPED is the only way a documented command is not run: a pattern, the reason, and where the same thing
is tested instead. It is kept short, and every entry must still match a documented command (the test
asserts both), so it cannot hide a command that changed.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BLOCK = re.compile(r"^```(\w*)\n(.*?)^```", re.S | re.M)
# programs a command starts with: a line of an unlabelled block starting with one is a command hiding
# from the test (the test fails on it)
PROGRAMS = ("grade ", "simiam ", "python ", "python3 ", "pip ", "dask ", "sudo ")


@dataclass(frozen=True)
class Skip:
    """Documented commands not run: those with a line matching `pattern` (scope "line"), or every line
    of a block with one (scope "block"); `reason` says why and where it is tested instead."""

    pattern: str
    reason: str
    scope: str = "line"

    def matches(self, text: str) -> bool:
        return re.search(self.pattern, text) is not None


SKIPPED = (
    Skip(r"^python -m pytest$", "the whole suite, which this test is part of"),
    Skip(r"^(python3 -m venv|\. \S*/activate$|pip install)",
         "installs into a new environment: tests/packaging/test_wheel.py installs the wheel in a fresh venv "
         "and runs grade, simiam run and migrate from it; here the suite's own install is used"),
    Skip(r"--executor dask|^dask ", "needs a Dask cluster (tests/batch/test_batch_dask.py runs a local one)"),
    Skip(r"(--batch|^grade similarity week\d) (\"[^\"]+\.zip\"|\S+\.zip\b)",
         "a course platform's download, which the checkout does not hold: tests/batch/test_batch_intake.py "
         "builds Canvas, Moodle and Gradescope downloads in their real layouts and reads these options "
         "from the command line (test_the_command_line_reads_the_intake_options); "
         "tests/batch/test_batch_similarity.py runs grade similarity and --similarity on a Canvas one"),
    Skip(r"^grade selfcheck", "every week's solutions, stubs and wrong versions: minutes of CPU "
         "(tests/platforms/test_selfcheck.py runs it week by week)"),
    Skip(r"AUTOGRADER_ROOT=|GRADE_ROOT=|COURSERA_SHARED=",
         "the platform image's own scripts, in a fresh mktemp folder and (Gradescope, PrairieLearn) as "
         "root: tests/platforms (test_gradescope_bundle.py, test_prairielearn.py, "
         "test_coursera.py) run them in a temporary root", scope="block"),
    Skip(r"benchmarks/|grader\.sandbox\.bench|^simiam bench|importtime|pythonX\.Y|batch-main|<branch>|"
         r"import numpy",
         "a benchmark (docs/performance.md): minutes of CPU each, its figures measured by hand; "
         "tests/benchmarks runs each benchmark's code on a small case", scope="block"),
)


@dataclass(frozen=True)
class Command:
    """One documented command: where it is written, its text, and the folder it runs in ("student" for
    a handout README, else "checkout"); `block` numbers its block within the file."""

    file: str
    line: int
    text: str
    block: int
    folder: str

    def where(self) -> str:
        return f"{self.file}:{self.line}: {self.text}"


def without_comment(line: str) -> str:
    """`line` without its `# comment` (a '#' starting a word, outside quotes, as bash reads it)."""
    quote = ""
    for k, ch in enumerate(line):
        if quote:
            quote = "" if ch == quote else quote
        elif ch in "'\"":
            quote = ch
        elif ch == "#" and (k == 0 or line[k - 1].isspace()):
            return line[:k]
    return line


def doc_files(root: Path = ROOT) -> list[Path]:
    return [root / "README.md", *sorted((root / "docs").glob("*.md")),
            *sorted((root / "assignments").glob("week*/README.md"))]


def commands_in(text: str, file: str) -> tuple[list[Command], list[str]]:
    """(the commands of `text`'s bash blocks, lines of its unlabelled blocks that look like commands)."""
    folder = "student" if file.startswith("assignments/") else "checkout"
    found, hidden = [], []
    for b, m in enumerate(BLOCK.finditer(text)):
        first = text[:m.start()].count("\n") + 2
        lines = m.group(2).splitlines()
        if m.group(1) == "":
            hidden += [f"{file}:{first + k}: {ln}" for k, ln in enumerate(lines) if ln.startswith(PROGRAMS)]
        if m.group(1) not in ("bash", "sh", "shell"):
            continue
        pending, start = "", 0
        for k, raw in enumerate(lines):
            line = without_comment(raw).strip()
            if not pending:
                start = first + k
            if line.endswith("\\"):
                pending += line[:-1] + " "
                continue
            line = (pending + line).strip()
            pending = ""
            if line:
                found.append(Command(file, start, " ".join(line.split()), b, folder))
    return found, hidden


def documented(root: Path = ROOT) -> tuple[list[Command], list[str]]:
    """Every command of the docs, in file order, and the command-like lines of unlabelled blocks."""
    commands, hidden = [], []
    for path in doc_files(root):
        found, loose = commands_in(path.read_text(encoding="utf-8"), path.relative_to(root).as_posix())
        commands += found
        hidden += loose
    return commands, hidden


def skip_of(command: Command, block: list[Command]) -> Skip | None:
    """The SKIPPED entry that keeps `command` (of `block`) from running, or None."""
    for skip in SKIPPED:
        if skip.scope == "block" and any(skip.matches(c.text) for c in block):
            return skip
    steps = [s for s in command.text.split(" && ")]
    if all(any(skip.matches(s) for skip in SKIPPED if skip.scope == "line") for s in steps):
        return next(skip for skip in SKIPPED if skip.scope == "line" and skip.matches(steps[-1]))
    return None


def runnable(command: Command) -> str:
    """The command as run: its install steps (SKIPPED, `a && b` chains) left out."""
    steps = [s for s in command.text.split(" && ")
             if not any(skip.matches(s) for skip in SKIPPED if skip.scope == "line")]
    return " && ".join(steps)


@dataclass
class Ran:
    """What a command did: its exit status, output (stdout and stderr) and the folder it ended in."""

    returncode: int
    output: str
    cwd: Path


def run(text: str, cwd: Path, env: dict[str, str], marker: Path, timeout: float = 600.0) -> Ran:
    """Run one command line with bash in `cwd`, as a reader's terminal would; the folder it ends in
    (after a `cd`, written to `marker`) is where the block's next line runs."""
    script = f"{text}\nstatus=$?\npwd > {str(marker)!r}\nexit $status\n"
    done = subprocess.run(["bash", "-c", script], cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=timeout)
    where = Path(marker.read_text().strip()) if marker.exists() else cwd
    marker.unlink(missing_ok=True)
    return Ran(done.returncode, done.stdout + done.stderr, where)


def scripts() -> Path:
    """The folder of this install's `grade` and `simiam` (beside the running python in a venv; else where
    the shell finds them)."""
    beside = Path(sys.executable).parent
    if (beside / "grade").exists():
        return beside
    found = shutil.which("grade")
    if found is None:
        raise RuntimeError("the grade command is not installed (pip install -e '.[test]')")
    return Path(found).parent


def clean_env(home: Path) -> dict[str, str]:
    """The environment of a reader's shell: this suite's install on PATH, `~` a temporary home, and the
    machine's pip settings (its index, certificates, proxies) as a reader's shell has them."""
    env = {k: v for k, v in os.environ.items() if k.startswith("PIP_") or k.lower().endswith("_proxy")}
    return {**env, "PATH": f"{scripts()}:/usr/bin:/bin", "HOME": str(home),
            "LANG": "C.UTF-8", "TERM": "dumb", "COLUMNS": "100"}
