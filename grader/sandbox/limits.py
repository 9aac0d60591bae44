"""Resource limits for one student's worker (applied by the worker itself: grader.inside.rlimits).

Time is enforced twice: by the grader per call and per grading (trusted, it kills the whole process tree),
and by the kernel's RLIMIT_CPU on the worker. The grader's limits are on the student's own time, the
worker's CPU time plus the time it slept (grader.sandbox.worker_clock), never on time a loaded machine held
it up; every wait also has a wall bound (`stall_seconds`, `total_wall_seconds`), past which the wait is the
machine's fault, not the student's (grader.grading redoes the check). One budget serves every worker and
session of a grading (grader.sandbox.time_budget). Memory, file size, core dumps, open files and
the number of processes are kernel rlimits set in the worker before any student code runs. RLIMIT_NPROC
counts processes per real uid and never binds for root, so the runner starts the worker under a dedicated
unprivileged uid when the grader runs as root.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass


@dataclass(frozen=True)
class Limits:
    """Limits for one submission. Times in seconds, sizes in bytes."""

    call_seconds: float = 2.0          # own time (CPU + sleep) of one request (a probe, a scenario step...)
    start_seconds: float = 10.0        # own time of the starting worker until it reports ready
    total_seconds: float = 120.0       # own time of all calls of a grading together (every worker, session)
    stall_seconds: float = 30.0        # wall bound of one request or start: past it, the machine stalled
    total_wall_seconds: float = 600.0  # wall bound of all calls of a grading together
    cpu_seconds: int = 120             # RLIMIT_CPU of one worker process (kernel-enforced)
    memory_bytes: int = 1024 * 2**20   # RLIMIT_AS per process (a week-4 worker maps ~110 MB)
    file_bytes: int = 8 * 2**20        # RLIMIT_FSIZE: largest file the worker may write (in its private /tmp)
    open_files: int = 64               # RLIMIT_NOFILE
    processes: int = 16                # RLIMIT_NPROC for the worker's uid (threads count too)
    output_bytes: int = 64 * 1024      # student stdout+stderr kept for feedback; the rest is counted, dropped
    tmp_bytes: int = 16 * 2**20        # size of the private /tmp (bubblewrap only)

    def to_json(self) -> dict:
        return asdict(self)

    def for_worker(self, cpu_left: float) -> dict:
        """The rlimits the worker applies to itself, with CPU capped by the submission's time left."""
        cpu = max(1, min(self.cpu_seconds, int(cpu_left) + 1))
        return {"cpu": cpu, "memory": self.memory_bytes, "file": self.file_bytes,
                "open_files": self.open_files, "processes": self.processes}
