"""Load a submission folder as a fresh, uniquely named package.

Student files import each other relatively (`from .go_to_goal import GoToGoal`), so the folder is
imported as one package. Every load gets a new package name, so two loads never share module objects.
Nothing is added to sys.path and no bytecode is read from or written into the folder: sources are
compiled in memory. A narrow meta-path finder resolves only the names of registered submission packages.

Problems are collected, not raised: `Submission.errors` is a list of LoadError(file, line, message)
a student can act on (syntax errors, exceptions while importing, missing files, missing functions).
"""

from __future__ import annotations

import importlib
import importlib.machinery
import importlib.util
import itertools
import sys
import traceback
import types
from dataclasses import dataclass, field
from pathlib import Path

_PREFIX = "simiam_submission_"
_counter = itertools.count(1)


@dataclass(frozen=True)
class LoadError:
    """A problem with one student file: `file` (name inside the folder), `line` (1-based or None)."""

    file: str
    line: int | None
    message: str

    def __str__(self) -> str:
        where = f"{self.file}:{self.line}" if self.line else self.file
        return f"{where}: {self.message}"

    def to_json(self) -> dict:
        return {"file": self.file, "line": self.line, "message": self.message}


@dataclass
class Submission:
    """A loaded submission: `modules` by file stem ("go_to_goal"), `errors` (empty when all is well)."""

    folder: Path
    package: str
    modules: dict[str, types.ModuleType] = field(default_factory=dict)
    errors: list[LoadError] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        """True when every file loaded and defines what the week needs."""
        return not self.errors

    def module(self, name: str) -> types.ModuleType:
        """The module `name` ("qb_supervisor"); KeyError with a clear message if it did not load."""
        if name not in self.modules:
            raise KeyError(f"{name}.py was not loaded" + (f" ({self.errors[0]})" if self.errors else ""))
        return self.modules[name]

    def unload(self) -> None:
        """Forget the package (drop its modules from sys.modules)."""
        _finder.folders.pop(self.package, None)
        for key in [k for k in sys.modules if k == self.package or k.startswith(self.package + ".")]:
            del sys.modules[key]


class _SourceOnlyLoader(importlib.machinery.SourceFileLoader):
    """Compile from source every time: never read or write __pycache__ in the student's folder."""

    def get_code(self, fullname):
        path = self.get_filename(fullname)
        return self.source_to_code(self.get_data(path), path)

    def set_data(self, path, data, *, _mode=0o666):  # pragma: no cover - never called by get_code
        return None


class _SubmissionFinder:
    """Finds `simiam_submission_N.<stem>` in the folder registered for that package, nothing else.

    A meta path finder needs only find_spec. It does not derive from importlib.abc.MetaPathFinder, whose
    import (importlib.resources, tempfile, shutil, ...) costs every sandboxed worker about 10 ms of CPU."""

    def __init__(self) -> None:
        self.folders: dict[str, Path] = {}

    def find_spec(self, fullname, path=None, target=None):
        package, _, stem = fullname.partition(".")
        folder = self.folders.get(package)
        if folder is None or not stem or "." in stem:
            return None
        source = folder / f"{stem}.py"
        if not source.is_file():
            return None
        return importlib.util.spec_from_file_location(
            fullname, source, loader=_SourceOnlyLoader(fullname, str(source))
        )


_finder = _SubmissionFinder()


def _install_finder() -> None:
    if _finder not in sys.meta_path:
        sys.meta_path.insert(0, _finder)


def _new_package(folder: Path) -> str:
    name = f"{_PREFIX}{next(_counter)}"
    spec = importlib.machinery.ModuleSpec(name, None, is_package=True)
    spec.submodule_search_locations = []  # only our finder resolves submodules
    package = importlib.util.module_from_spec(spec)
    package.__path__ = []
    sys.modules[name] = package
    _finder.folders[name] = folder
    return name


def _error_from_exception(exc: BaseException, folder: Path, default_file: str, package: str) -> LoadError:
    """Say where in the student's folder an import failed and why."""
    if isinstance(exc, SyntaxError):
        name = Path(exc.filename).name if exc.filename else default_file
        kind = "indentation error" if isinstance(exc, IndentationError) else "syntax error"
        return LoadError(name, exc.lineno, f"{kind}: {exc.msg}")
    file, line = locate_in_folder(exc, folder)
    text = str(exc).replace(f"{package}.", "")  # say "go_to_goal", not "simiam_submission_7.go_to_goal"
    message = f"{type(exc).__name__}: {text}" if text else type(exc).__name__
    return LoadError(file or default_file, line, f"error while importing: {message}")


def locate_in_folder(exc: BaseException, folder: Path) -> tuple[str | None, int | None]:
    """The innermost traceback frame of `exc` that lies in `folder`: (file name, line), or (None, None)."""
    folder = Path(folder).resolve()
    found: tuple[str | None, int | None] = (None, None)
    for frame in traceback.extract_tb(exc.__traceback__):
        try:
            path = Path(frame.filename).resolve()
        except (OSError, ValueError):
            continue
        if path.parent == folder:
            found = (path.name, frame.lineno)
    return found


def load_submission(folder: Path | str, week) -> Submission:
    """Import the student files of `week` (a Week or a week number) from `folder`.

    Files are imported in the week's order; each missing file, syntax error, import-time exception
    and missing function or class becomes one LoadError. Modules that imported are in `modules`.
    """
    from simiam.course.weeks import get_week

    config = get_week(week) if isinstance(week, int) else week
    folder = Path(folder).resolve()
    sub = Submission(folder=folder, package="")
    if not folder.is_dir():
        sub.errors.append(LoadError(str(folder), None, "no such folder"))
        return sub
    _install_finder()
    sub.package = _new_package(folder)
    seen: set[tuple] = set()
    for file in config.student_files:
        stem = file.removesuffix(".py")
        if not (folder / file).is_file():
            sub.errors.append(LoadError(file, None, f"missing file: {file} should be in {folder}"))
            continue
        try:
            sub.modules[stem] = importlib.import_module(f"{sub.package}.{stem}")
        except BaseException as exc:  # noqa: BLE001 - any failure of student code is reported, not raised
            if isinstance(exc, KeyboardInterrupt):
                raise
            err = _error_from_exception(exc, folder, file, sub.package)
            key = (err.file, err.line, err.message)
            if key not in seen:  # a broken file imported by a sibling is reported once
                seen.add(key)
                sub.errors.append(err)
    for file, names in config.required_names.items():
        module = sub.modules.get(file.removesuffix(".py"))
        if module is None:
            continue
        for name in names:
            if not _has(module, name):
                sub.errors.append(LoadError(file, None, f"{file} must define {name}, but it is not there"))
    return sub


def _has(module: types.ModuleType, dotted: str) -> bool:
    """True if `module` has `dotted` ("QBSupervisor.update_odometry" looks inside the class)."""
    obj: object = module
    for part in dotted.split("."):
        if not hasattr(obj, part):
            return False
        obj = getattr(obj, part)
    return True
