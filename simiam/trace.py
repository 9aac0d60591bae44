"""`Trace`: the record of one run, columnar, as plain JSON (and a flat CSV). The viewer and the grader's
report read only this (docs/design.md, Seam 2). Row 0 is the state before the first step.

The columns are the fixed ones (`HEAD`, `TAIL`) plus one per debug signal the run recorded, named by the
signal; the header's `signals` declares them (name, kind, size of points), so that a reader needs no
registry. A trace without `signals` (written before they were declared) recorded weeks 1-4's five.
`ending` says how the run ended (`Ending`).
"""

from __future__ import annotations

import csv
import io
import json
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path
from typing import Any

from simiam import safe_write
from simiam.robot.quickbot import IR_MOUNTS
from simiam.signals import WEEKS_1_TO_4, declared, from_headers, headers

FORMAT = "simiam-trace/1"

HEAD = ("t", "x", "y", "theta", "x_est", "y_est", "theta_est", "ticks_r", "ticks_l", "vel_r", "vel_l",
        "ir_raw", "ir_range")
TAIL = ("state", "collided")
# What a trace of weeks 1-4 records (and every trace without a `signals` header).
WEEKS_1_TO_4_SIGNALS: list[dict] = headers(declared(WEEKS_1_TO_4), len(IR_MOUNTS))
COLUMNS = HEAD + WEEKS_1_TO_4 + TAIL  # the columns of such a trace, in order


class EndReason(str, Enum):
    """Why a run stopped."""

    TIME_UP = "time_up"                  # all the steps asked for ran
    COLLISION = "collision"              # the robot hit something
    UNTIL = "until"                      # the caller's condition became true (e.g. the goal was reached)
    INVALID_COMMAND = "invalid_command"  # the brain answered something that is not a command
    BRAIN_ERROR = "brain_error"          # the brain raised (the student's exception, a dead worker)
    STUCK = "stuck"                      # the brain did not answer in time (an endless loop)


BROKEN = (EndReason.INVALID_COMMAND, EndReason.BRAIN_ERROR, EndReason.STUCK)


@dataclass(frozen=True)
class Ending:
    """How a run ended: the `reason`, the `step` and time `t` it ended at (for a broken brain: the step
    that failed, which is not in the trace), a `message` in words, and the brain's exception in `error`
    (kept in memory for the caller's own words; never written to JSON)."""

    reason: EndReason
    step: int
    t: float
    message: str = ""
    error: BaseException | None = field(default=None, compare=False, repr=False)

    @property
    def broken(self) -> bool:
        """The brain broke the run (an exception, an invalid command, no answer in time)."""
        return self.reason in BROKEN

    def to_json(self) -> dict:
        return {"reason": self.reason.value, "step": self.step, "t": self.t, "message": self.message}

    @classmethod
    def from_json(cls, data: Any) -> Ending | None:
        """An Ending from `to_json()` output; None for None or anything not a recorded ending."""
        if not isinstance(data, dict):
            return None
        try:
            return cls(EndReason(data.get("reason")), int(data.get("step", 0)), float(data.get("t", 0.0)),
                       str(data.get("message", "")))
        except (ValueError, TypeError):
            return None


@dataclass
class Trace:
    """One run: header (week, dt, world, robot, start, goal, signals, meta), the per-step columns, the
    first collision ({"step", "t", "pose"} or None) and how the run ended."""

    week: int
    dt: float
    world: dict
    robot: dict
    start: list[float]
    goal: list[float] | None = None
    steps: dict[str, list] = field(default_factory=dict)
    collision: dict | None = None
    meta: dict = field(default_factory=dict)
    signals: list[dict] = field(default_factory=lambda: list(WEEKS_1_TO_4_SIGNALS))
    ending: Ending | None = None

    def __post_init__(self) -> None:
        self.signals = from_headers(self.signals)
        clash = [s["name"] for s in self.signals if s["name"] in HEAD + TAIL]
        if clash or len({s["name"] for s in self.signals}) != len(self.signals):
            raise ValueError(f"signal names must be unique and not a fixed column: {clash or self.signals}")
        self.signal_names: tuple[str, ...] = tuple(s["name"] for s in self.signals)
        if not self.steps:
            self.steps = {c: [] for c in self.columns}

    @property
    def columns(self) -> tuple[str, ...]:
        """The per-step columns, in order: HEAD, one per signal, TAIL."""
        return HEAD + self.signal_names + TAIL

    def __len__(self) -> int:
        return len(self.steps["t"])

    @property
    def seconds(self) -> float:
        """Simulated time covered (the last row's t)."""
        return self.steps["t"][-1] if self.steps["t"] else 0.0

    def to_json(self) -> dict:
        """The trace as a JSON-ready dict (format "simiam-trace/1")."""
        return {"format": FORMAT, "week": self.week, "dt": self.dt, "seconds": self.seconds,
                "world": self.world, "robot": self.robot, "start": list(self.start),
                "goal": None if self.goal is None else list(self.goal),
                "signals": self.signals, "steps": self.steps, "collision": self.collision,
                "ending": None if self.ending is None else self.ending.to_json(), "meta": self.meta}

    @classmethod
    def from_json(cls, data: dict | str) -> Trace:
        """Read a trace back from `to_json()` output (a dict or its JSON text)."""
        if isinstance(data, str):
            data = json.loads(data)
        if not isinstance(data, dict) or data.get("format") != FORMAT:
            raise ValueError(f"not a {FORMAT} trace")
        signals = from_headers(data.get("signals", WEEKS_1_TO_4_SIGNALS))
        columns = HEAD + tuple(s["name"] for s in signals) + TAIL
        steps = data["steps"]
        missing = [c for c in columns if c not in steps]
        if missing:
            raise ValueError(f"trace is missing the columns {', '.join(map(str, missing))}")
        return cls(week=data["week"], dt=data["dt"], world=data["world"], robot=data["robot"],
                   start=data["start"], goal=data.get("goal"), steps={c: steps[c] for c in columns},
                   collision=data.get("collision"), meta=data.get("meta", {}), signals=signals,
                   ending=Ending.from_json(data.get("ending")))

    def _n_ir(self) -> int:
        mounts = self.robot.get("ir_mounts") if isinstance(self.robot, dict) else None
        if mounts:
            return len(mounts)
        return max((len(r) for r in self.steps["ir_raw"] if isinstance(r, list)), default=0)

    def _spread(self) -> dict[str, list[str]]:
        """Each column's CSV headings: lists spread over numbered columns, signals by their kind."""
        n = self._n_ir()
        out = {c: [c] for c in self.columns}
        out["ir_raw"] = [f"ir_raw_{i}" for i in range(1, n + 1)]
        out["ir_range"] = [f"ir_range_{i}" for i in range(1, n + 1)]
        for s in self.signals:
            name = s["name"]
            if s["kind"] == "vector2":
                out[name] = [f"{name}_x", f"{name}_y"]
            elif s["kind"] == "points":
                out[name] = [f"{name}_{a}{i}" for a in "xy" for i in range(1, s["size"] + 1)]
        return out

    def csv_header(self) -> list[str]:
        """The flat CSV columns: lists are spread over numbered columns (ir_raw_1..N, u_ao_x, u_ao_y,
        ir_points_wf_x1..xN, ir_points_wf_y1..yN: a vector signal NAME_x/NAME_y, points NAME_xI/NAME_yI)."""
        spread = self._spread()
        return [h for c in self.columns for h in spread[c]]

    def csv_rows(self) -> list[list[Any]]:
        """The CSV body rows (None, and a list of the wrong length, become empty cells)."""
        widths = {c: len(h) for c, h in self._spread().items()}
        points = {s["name"] for s in self.signals if s["kind"] == "points"}
        rows = []
        for k in range(len(self)):
            row: list[Any] = []
            for c in self.columns:
                val = self.steps[c][k]
                width = widths[c]
                if c in points and isinstance(val, list) and len(val) == 2:
                    val = list(val[0]) + list(val[1])
                if width == 1 and not isinstance(val, list):
                    row.append(val)
                elif isinstance(val, list) and len(val) == width:
                    row += val
                else:
                    row += [None] * width
            rows.append(["" if v is None else (repr(v) if isinstance(v, float) else v) for v in row])
        return rows

    def write(self, directory: str | Path, stem: str = "trace") -> tuple[Path, Path]:
        """Write `<stem>.csv` and `<stem>.json` into `directory` (never through a link: simiam.safe_write);
        returns (csv_path, json_path)."""
        directory = Path(directory)
        table = io.StringIO(newline="")
        out = csv.writer(table)
        out.writerow(self.csv_header())
        out.writerows(self.csv_rows())
        csv_path = safe_write.write_text(directory / f"{stem}.csv", table.getvalue())
        json_path = safe_write.write_text(directory / f"{stem}.json",
                                          json.dumps(self.to_json(), allow_nan=False, separators=(",", ":")))
        return csv_path, json_path
