"""Where the grading processes run: this machine (:class:`LocalExecutor`) or a Dask cluster.

Both take the same tasks (plain dicts) and the same grading function, and report the same outcomes
(see :class:`grader.batch.pool.WorkerPool`), so a class graded on a cluster gets byte-identical results.
On Dask each task runs in a killable child process on the worker machine, so the wall budget and the
``timeout``/``crashed`` statuses mean the same thing there.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable
from typing import Any

from grader.batch.pool import GradeFn, WorkerPool, function_ref

OnDone = Callable[[dict, dict], None]


class ExecutorError(Exception):
    """The executor cannot run at all (Dask missing, scheduler unreachable)."""


class LocalExecutor:
    """``jobs`` grading processes on this machine."""

    def __init__(self, jobs: int, budget_s: float) -> None:
        self.jobs, self.budget_s = jobs, budget_s

    def describe(self) -> dict:
        return {"executor": "local", "jobs": self.jobs, "budget_s": self.budget_s}

    def run(self, grade_fn: GradeFn | str, tasks: Iterable[dict], on_done: OnDone) -> None:
        WorkerPool(grade_fn, self.jobs, self.budget_s).run(tasks, on_done)


def grade_isolated(ref: str, task_json: str, budget_s: float) -> str:
    """Dask task body: grade one task in a killable child process on this worker; the outcome as JSON."""
    outcomes: list[dict] = []
    WorkerPool(ref, 1, budget_s).run([json.loads(task_json)], lambda _task, outcome: outcomes.append(outcome))
    return json.dumps(outcomes[0])


class DaskExecutor:
    """Grade on a Dask distributed cluster: ``scheduler`` is its address (``tcp://host:8786``).

    Without an address a private loopback ``LocalCluster`` of ``jobs`` workers is started, which is
    mostly useful to try the set-up. ``client`` may be given directly (tests).
    """

    def __init__(self, scheduler: str | None, budget_s: float, jobs: int = 1, client: Any = None,
                 connect_timeout_s: float = 20.0) -> None:
        self.scheduler, self.budget_s, self.jobs, self.client = scheduler, budget_s, jobs, client
        self.connect_timeout_s = connect_timeout_s

    def describe(self) -> dict:
        return {"executor": "dask", "scheduler": self.scheduler, "budget_s": self.budget_s}

    def _connect(self) -> tuple[Any, list[Any]]:
        try:
            from distributed import Client, LocalCluster
        except ImportError:
            raise ExecutorError("the Dask executor needs dask.distributed: pip install '.[dask]'") from None
        if self.client is not None:
            return self.client, []
        try:
            if self.scheduler:
                client = Client(self.scheduler, timeout=f"{self.connect_timeout_s}s")
                return client, [client]
            cluster = LocalCluster(n_workers=max(1, self.jobs), threads_per_worker=1, host="127.0.0.1",
                                   dashboard_address=None, processes=True)
            client = Client(cluster)
            return client, [client, cluster]
        except (OSError, TimeoutError) as exc:
            raise ExecutorError(f"cannot reach the Dask scheduler at {self.scheduler}: {exc}") from None

    def run(self, grade_fn: GradeFn | str, tasks: Iterable[dict], on_done: OnDone) -> None:
        from distributed import as_completed

        client, owned = self._connect()
        ref = function_ref(grade_fn)
        in_flight: dict[Any, dict] = {}
        done = as_completed()
        try:
            # keep the scheduler busy without holding 400 submissions' bytes in memory at once
            window = max(2, 2 * sum(client.nthreads().values()))
            for task in tasks:
                future = client.submit(grade_isolated, ref, json.dumps(task), self.budget_s, pure=False,
                                       key=f"grade-{task.get('student', 'x')}-{len(in_flight)}-{id(task)}")
                in_flight[future] = task
                done.add(future)
                while len(in_flight) >= window:
                    self._finish(next(done), in_flight, on_done)
            while in_flight:
                self._finish(next(done), in_flight, on_done)
        finally:
            for future in in_flight:
                future.cancel()
            for resource in owned:
                resource.close()

    @staticmethod
    def _finish(future: Any, in_flight: dict[Any, dict], on_done: OnDone) -> None:
        task = in_flight.pop(future)
        try:
            outcome = json.loads(future.result())
        except Exception as exc:  # noqa: BLE001 - KilledWorker, lost connection...: this student only
            outcome = {"status": "crashed", "value": None, "seconds": 0.0,
                       "message": f"the Dask worker failed on this submission: {type(exc).__name__}: {exc}"}
        on_done(task, outcome)
