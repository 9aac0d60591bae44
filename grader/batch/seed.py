"""What ``--seed`` accepts: a number, a batch output folder, or that folder's ``.seed`` file.

Regrading one student elsewhere with the hidden set of a batch needs that batch's seed; the folder keeps
it in ``.seed`` as JSON (``{"seed": N, "set_by": ...}``), so ``--seed graded/``,
``--seed graded/.seed`` and ``--seed "$(cat graded/.seed)"`` all give N.
"""

from __future__ import annotations

import json
from pathlib import Path

from grader.batch.store import SEED

MAX_SEED = 2**31            # a batch's own seeds are drawn below this (grader.batch.store.folder_seed)
MAX_DIGITS = 18           # a number given on the command line
MAX_SEED_FILE = 4096        # bytes of a .seed file read: it holds one small JSON object


def parse_seed(text: str) -> int:
    """The seed ``text`` names (ValueError, saying what was expected, if none)."""
    text = str(text).strip()
    number = _number(text)
    if number is not None:
        return number
    stored = _from_json(text)       # what `cat graded/.seed` prints
    if stored is not None:
        return stored
    path = Path(text)
    if path.is_dir():
        path = path / SEED
    if path.is_file():
        with path.open("rb") as stream:
            stored = _from_json(stream.read(MAX_SEED_FILE).decode("utf-8", "replace"))
        if stored is not None:
            return stored
        raise ValueError(f"--seed {text}: {path} holds no seed (expected {{\"seed\": N}})")
    if path.name == SEED or Path(text).is_dir():
        raise ValueError(f"--seed {text}: there is no {path}: that folder was not the output of a batch")
    raise ValueError(f"--seed {text!r}: expected a whole number, a batch output "
                     f"folder, or its {SEED} file")


def _number(text: str) -> int | None:
    """A whole number of at most 18 digits (any sign: `grade weekN --seed -3` always worked)."""
    digits = text[1:] if text[:1] in "+-" else text
    if not digits.isascii() or not digits.isdigit() or len(digits) > MAX_DIGITS:
        return None
    return int(text)


def _from_json(text: str) -> int | None:
    try:
        value = json.loads(text)
    except ValueError:
        return None
    seed = value.get("seed") if isinstance(value, dict) else None
    return seed if type(seed) is int and 0 <= seed < MAX_SEED else None
