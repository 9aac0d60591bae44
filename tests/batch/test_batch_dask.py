"""The Dask executor gives the same per-student results as the local one (a loopback LocalCluster)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from batch_helpers import HANG_BUDGET_S, make_class

from grader.batch import runner
from grader.batch.executors import DaskExecutor, ExecutorError
from grader.batch.runner import BatchOptions, run_batch

distributed = pytest.importorskip("distributed")

FAKE = "batch_fake_grader:fake_grade"


def per_student(out: Path) -> dict[str, dict]:
    found = {}
    for path in out.glob("*.json"):
        if path.name != "batch.json":
            result = json.loads(path.read_text())
            result.pop("timing")
            found[path.stem] = result
    return found


def test_dask_matches_local(tmp_path: Path, monkeypatch) -> None:
    monkeypatch.setattr(runner, "grader_fingerprint", lambda: "fake-grader")
    answers = {"a": "score 3", "b": "score 10", "c": "crash", "d": "hang", "e": "invalid"}
    make_class(tmp_path / "class", answers, zipped=("b",))
    base = {"week": 3, "batch_dir": tmp_path / "class", "seed": 3, "quiet": True, "budget_s": HANG_BUDGET_S}
    run_batch(BatchOptions(**base, out=tmp_path / "local", jobs=2), grade_fn=FAKE)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False, protocol="tcp://",
                                  host="127.0.0.1",
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        report = run_batch(BatchOptions(**base, out=tmp_path / "dask", executor="dask"), grade_fn=FAKE,
                           executor=DaskExecutor(None, HANG_BUDGET_S, client=client))
    assert report["executor"] == "dask"
    local, dask = per_student(tmp_path / "local"), per_student(tmp_path / "dask")
    assert local == dask
    assert {sid: r["status"] for sid, r in dask.items()} == {"a": "graded", "b": "graded", "c": "crashed",
                                                              "d": "timeout", "e": "invalid"}


def test_unreachable_scheduler_is_a_clear_error() -> None:
    executor = DaskExecutor("tcp://127.0.0.1:9", 5.0, connect_timeout_s=1.0)
    with pytest.raises(ExecutorError, match="cannot reach the Dask scheduler"):
        executor._connect()
