"""Where a timed-out call was stuck: the student's innermost frame, read from the worker's stack dump.

When a call runs past its deadline the runner asks the worker for a stack dump (SIGUSR1, which the worker's
bootstrap registered with `faulthandler` on a private pipe) before killing it. faulthandler writes from a C
signal handler, so a `while True: pass` or a long `time.sleep` cannot hold it back; student code can only
unregister it, which loses the location and gains nothing.

The dump is untrusted text (the student's code may write to that pipe too). `find_stuck` reads at most
MAX_DUMP_BYTES, accepts only lines matching faulthandler's exact format, and keeps a frame only if its file
is one of the submission's own files (by name, in the folder the worker sees) and its line exists in that
file. The function's qualified name (`GoToGoal.execute`) comes from parsing the grader's copy of that file
with `ast` (never run). Nothing from the dump reaches a message except a checked file name, a line number
and an identifier.
"""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass
from pathlib import Path

MAX_DUMP_BYTES = 64 * 1024
_THREAD = re.compile(r"(?:Current thread|Thread) 0x([0-9a-f]{1,16}) \(most recent call first\):")
_FRAME = re.compile(r'  File "(/[^"\n]{1,4000})", line (\d{1,7}) in '
                    r"([A-Za-z_][A-Za-z0-9_]{0,99}|<[a-z]{1,20}>)")
_FILE_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]{0,99}\.py")


@dataclass(frozen=True)
class Stuck:
    """A place in the student's code: file name (no folder), line, function (qualified where known)."""

    file: str
    line: int
    function: str

    def __str__(self) -> str:
        where = "at module level" if self.function == "<module>" else f"in {self.function}"
        return f"{self.file}:{self.line} {where}"

    def to_json(self) -> dict:
        return {"file": self.file, "line": self.line, "function": self.function}


def find_stuck(dump: bytes, worker_folder: str, source_folder: Path, main_thread: int | None) -> Stuck | None:
    """The innermost frame of the student's code in `dump`, or None.

    `worker_folder`: the submission folder as the worker sees it (its frames' file names start with it);
    `source_folder`: the grader's copy of the same files (for the names, line counts and qualified names);
    `main_thread`: the thread id the worker reported before any student code ran (the one serving calls).
    Frames of that thread are preferred; other threads count only if it shows no student frame.
    """
    text = dump[:MAX_DUMP_BYTES].decode("ascii", errors="replace")
    threads: list[tuple[int | None, list[tuple[str, int, str]]]] = []
    for raw in text.splitlines():
        header = _THREAD.fullmatch(raw)
        if header:
            threads.append((int(header.group(1), 16), []))
            continue
        frame = _FRAME.fullmatch(raw)
        if frame and threads:
            threads[-1][1].append((frame.group(1), int(frame.group(2)), frame.group(3)))
    # The serving thread first; then the others in dump order (a student thread may be the one looping).
    ordered = [t for t in threads if t[0] == main_thread] + [t for t in threads if t[0] != main_thread]
    folder = worker_folder.rstrip("/") + "/"
    for _ident, frames in ordered:
        for path, line, function in frames:  # innermost first
            stuck = _student_frame(path, line, function, folder, source_folder)
            if stuck is not None:
                return stuck
    return None


def _student_frame(path: str, line: int, function: str, folder: str, source_folder: Path) -> Stuck | None:
    if not path.startswith(folder):
        return None
    name = path[len(folder):]
    if not _FILE_NAME.fullmatch(name):
        return None
    source = source_folder / name
    try:
        if not source.is_file() or source.is_symlink():
            return None
        text = source.read_text(encoding="utf-8", errors="replace")
    except OSError:
        return None
    if not 1 <= line <= text.count("\n") + (not text.endswith("\n")):
        return None
    return Stuck(name, line, qualified_name(text, line, function))


def qualified_name(source: str, line: int, function: str) -> str:
    """`Class.method` for the innermost def around `line` whose name is `function`; else `function`."""
    if function.startswith("<"):
        return function
    try:
        tree = ast.parse(source)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return function
    best: list[str] = []

    def visit(node: ast.AST, scope: list[str]) -> None:
        nonlocal best
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                end = getattr(child, "end_lineno", None) or child.lineno
                if child.lineno <= line <= end:
                    inner = [*scope, child.name]
                    if not isinstance(child, ast.ClassDef) and child.name == function:
                        best = inner
                    visit(child, inner)
            else:
                visit(child, scope)

    try:
        visit(tree, [])
    except RecursionError:
        return function
    return ".".join(best) if best else function
