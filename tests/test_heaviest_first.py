"""The suite's own schedule (tests/heaviest_first.py): the heaviest module is handed out first, the modules
that share the platforms' bundle stay on one worker, and every module the table names still exists (a
renamed module would silently fall back to the per-test guess)."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import heaviest_first
from heaviest_first import SECONDS, TOGETHER, HeaviestFirst, table
from xdist.scheduler import LoadScopeScheduling

ROOT = Path(__file__).resolve().parents[1]


class Config:
    """What the scheduler reads of pytest's config: two workers, xdist's default order."""

    option = SimpleNamespace(loadscopereorder=True)

    def getvalue(self, name: str) -> object:
        return {"tx": ["2*popen"]}[name]


class Worker:
    """What the scheduler talks to: the tests it was sent, in order."""

    def __init__(self, name: str) -> None:
        self.sent: list[int] = []
        self.shutting_down = False
        self.gateway = SimpleNamespace(id=name)

    def send_runtest_some(self, indices: list[int]) -> None:
        self.sent += indices

    def shutdown(self) -> None:
        self.shutting_down = True


def first_sent(kind: type[LoadScopeScheduling], collection: list[str]) -> list[str]:
    """The modules of the tests each of two workers is sent first (one per worker, in their order)."""
    sched = kind(Config())
    workers = [Worker("gw0"), Worker("gw1")]
    for worker in workers:
        sched.add_node(worker)
    for worker in workers:
        sched.add_node_collection(worker, collection)
    sched.schedule()
    return [collection[w.sent[0]].split("::")[0] for w in workers]


COLLECTION = ([f"tests/many_light.py::test_{k}" for k in range(40)] + ["tests/one_long.py::test_it"]
              + [f"tests/middle.py::test_{k}" for k in range(3)])


def test_the_heaviest_module_is_sent_first(monkeypatch) -> None:
    monkeypatch.setitem(SECONDS, "tests/one_long.py", 60.0)
    monkeypatch.setitem(SECONDS, "tests/middle.py", 20.0)
    assert first_sent(HeaviestFirst, COLLECTION) == ["tests/one_long.py", "tests/middle.py"]
    # the wrong version, xdist's own order (most tests first), sends the long one last
    assert first_sent(LoadScopeScheduling, COLLECTION)[0] == "tests/many_light.py"


def test_modules_sharing_the_bundle_are_one_unit(monkeypatch) -> None:
    shared = sorted(TOGETHER)
    monkeypatch.setattr(heaviest_first, "SECONDS", {**SECONDS, **{module: 50.0 for module in shared}})
    collection = [f"{module}::test_a" for module in shared] + COLLECTION
    sched = HeaviestFirst(Config())
    assert {sched._split_scope(nodeid) for nodeid in collection[:len(shared)]} == {TOGETHER[shared[0]]}
    assert heaviest_first.expected_seconds(TOGETHER[shared[0]], len(shared)) == 50.0 * len(shared)
    # one worker gets both; the other the next heaviest
    assert first_sent(HeaviestFirst, collection) == [shared[0], "tests/many_light.py"]


def test_a_group_with_an_unmeasured_member_counts_its_measured_ones(monkeypatch) -> None:
    """The wrong version this catches handed the whole group out last, at PER_TEST a test, as soon as one
    member lacked a figure."""
    shared = sorted(TOGETHER)
    monkeypatch.setattr(heaviest_first, "SECONDS", {shared[0]: 80.0})
    assert heaviest_first.expected_seconds(TOGETHER[shared[0]], 4) == 80.0
    assert heaviest_first.expected_seconds("tests/unmeasured.py", 20) == 20 * heaviest_first.PER_TEST


def test_every_module_the_table_names_exists() -> None:
    named = set(SECONDS) | set(TOGETHER)
    assert [m for m in sorted(named) if not (ROOT / m).is_file()] == []


def test_the_table_is_read_from_durations() -> None:
    durations = ("12.50s call     tests/a/test_x.py::test_one[p-1]\n"
                 "1.50s setup    tests/a/test_x.py::test_one[p-1]\n"
                 "2.00s call     tests/a/test_y.py::test_two\n"
                 "(3 durations < 0.005s hidden.)\n")
    assert table(durations) == {"tests/a/test_x.py": 14.0}
