"""One grading's time budget: shared by every worker and every session the grading opens.

A grading may open a second session (weeks 5-7 run their scenarios on the course's earlier blocks:
grader.earlier), and a session starts a fresh worker after every kill; none of them starts with a fresh
budget. What is charged is the student's own time (grader.sandbox.worker_clock): the CPU time of every
worker while it served the grading (all threads and forks, read from /proc about every CPU_READ_EVERY
seconds and after every slow call), plus the time slow calls spent asleep. Time the machine held a worker
up is never charged. Where the workers' time cannot be read (no /proc) the wall time of each call is
charged instead (`blind`), and the grading's result says so.

`total_wall_seconds` bounds the wall time of all calls together, whatever the machine does: past it the
grading stops as stalled (a machine that slow cannot give a verdict; naps shorter than worker_clock's
FIRST_LOOK are not read, so this bound is also what ends code that naps in many short sleeps).
"""

from __future__ import annotations

import time

from grader.sandbox.worker_clock import CallClock, read

CPU_READ_EVERY = 0.5  # s of calls between two reads of a worker's CPU time (a read costs ~0.1 ms)


class TimeBudget:
    """The grading's time: `total_seconds` of the student's own time, `total_wall_seconds` of calls."""

    def __init__(self, total_seconds: float, total_wall_seconds: float) -> None:
        self.total_seconds = float(total_seconds)
        self.total_wall_seconds = float(total_wall_seconds)
        self.cpu = 0.0          # CPU seconds of the workers while they served this grading
        self.asleep = 0.0       # seconds slow calls spent asleep
        self.blind_wall = 0.0   # wall seconds of calls whose worker's time could not be read
        self.wall = 0.0         # wall seconds of every call
        self.calls = 0
        self.stalls: list[str] = []  # what each MachineStalled said, in order (grader.grading redoes)

    @property
    def used(self) -> float:
        """The student's time charged so far (seconds)."""
        return self.cpu + self.asleep + self.blind_wall

    @property
    def blind(self) -> bool:
        return self.blind_wall > 0

    def left(self) -> float:
        return self.total_seconds - self.used

    def charge(self, clock: CallClock | None, wall: float, meter: CpuMeter | None) -> None:
        """Charge one call that waited `wall` seconds, judged by `clock` (None: the call never waited),
        on the worker `meter` reads."""
        self.calls += 1
        self.wall += wall
        if clock is not None and clock.blind or meter is None or meter.blind:
            self.blind_wall += wall
            return
        if clock is not None and clock.looked:
            self.asleep += clock.asleep
            self.cpu += meter.since(clock.cpu_seen, force=True)
        else:
            self.cpu += meter.since(None, force=False)

    def to_json(self) -> dict:
        """What the result says of the grading's time ("measure": what the limits were judged on)."""
        return {"measure": "wall clock (this system cannot tell the worker's CPU time)" if self.blind
                else "the worker's CPU time and sleep", "used_seconds": round(self.used, 3),
                "cpu_seconds": round(self.cpu, 3), "asleep_seconds": round(self.asleep, 3),
                "wall_seconds": round(self.wall, 3), "total_seconds": self.total_seconds,
                "calls": self.calls, "stalls": len(self.stalls)}


class CpuMeter:
    """The CPU time one worker has used since it reported ready (read from /proc by its host pid)."""

    def __init__(self, pid: int | None) -> None:
        self.pid = pid
        first = read(pid)
        self.blind = first is None
        self.mark = first.cpu if first is not None else 0.0
        self.at = time.monotonic()

    def since(self, seen: float | None, force: bool) -> float:
        """CPU seconds since the last charge: read now (at most every CPU_READ_EVERY s unless `force`),
        else `seen` (the last look of a clock, when the worker is already gone); 0 when not read now."""
        now = time.monotonic()
        if not force and now - self.at < CPU_READ_EVERY:
            return 0.0
        reading = read(self.pid)
        cpu = reading.cpu if reading is not None else seen
        self.at = now
        if cpu is None or cpu < self.mark:
            return 0.0
        used, self.mark = cpu - self.mark, cpu
        return used

    def settle(self) -> float:
        """The CPU not charged yet (before the worker is killed)."""
        return self.since(None, force=True)
