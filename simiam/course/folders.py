"""Where a week's folder is when the command line names none: one rule for `grade`, `simiam run` and
`simiam migrate`.

    1. the current folder, if it is named weekN, in any case (you are inside your week folder);
    2. else ./weekN (you are in the folder that holds your week folders);
    3. else ./assignments/weekN (you are in the course checkout);
    4. else a clear message naming the three places looked at.

`--solutions` (instructors, in the course checkout) means the checkout's solutions/weekN; a student
package has no solutions/ and says so.
"""

from __future__ import annotations

import importlib
import sys
from pathlib import Path
from types import ModuleType

# The checkout this package was imported from (an editable install); in a wheel, site-packages.
CHECKOUT = Path(__file__).resolve().parents[2]


INSTRUCTOR_TOOLS = CHECKOUT / "instructor_tools"


class WeekFolderNotFound(ValueError):
    """No folder for the week where the rule looks; the message says where it looked and what to do."""


def default_week_folder(week: int, cwd: Path | None = None) -> Path:
    """The week-`week` folder by the rule above (relative to `cwd`, default the current folder)."""
    here = Path.cwd() if cwd is None else Path(cwd)
    name = f"week{int(week)}"
    if here.name.casefold() == name:  # Windows and macOS keep "Week3" as typed but take it for week3
        return here
    for candidate in (here / name, here / "assignments" / name):
        if candidate.is_dir():
            return candidate
    raise WeekFolderNotFound(
        f"no {name} folder here: looked at the current folder ({here} is not named {name}), ./{name} and "
        f"./assignments/{name}; go into your {name} folder (or the folder holding it), or name the "
        "folder on the command line"
    )


def solutions_folder(week: int) -> Path:
    """solutions/weekN of the course checkout; WeekFolderNotFound in a student package (no solutions)."""
    folder = CHECKOUT / "solutions" / f"week{int(week)}"
    if not folder.is_dir():
        raise WeekFolderNotFound(
            f"--solutions needs the course checkout (this installation has no {folder}): the reference "
            "solutions are not part of the student package"
        )
    return folder


def week_folder(week: int, path: str | Path | None = None, solutions: bool = False) -> Path:
    """The folder a command works on: PATH when given, solutions/weekN with `solutions`, else the rule."""
    if path is not None and str(path) != "":
        return Path(path).expanduser()
    if solutions:
        return solutions_folder(week)
    return default_week_folder(week)


class NotInCheckout(RuntimeError):
    """Instructor tooling asked for outside the course checkout (a student package does not hold it)."""


def instructor_tool(module: str) -> ModuleType:
    """`instructor_tools.<module>` from the course checkout this package runs from (an editable install);
    NotInCheckout in a student package, which holds no instructor tooling."""
    if not (INSTRUCTOR_TOOLS / f"{module}.py").is_file():
        raise NotInCheckout(
            f"instructor_tools/{module}.py is instructor tooling in the course checkout, not part of the "
            "student package: run this from the checkout (pip install -e .)"
        )
    if str(CHECKOUT) not in sys.path:
        sys.path.append(str(CHECKOUT))  # appended: never shadows an installed module
    return importlib.import_module(f"instructor_tools.{module}")
