"""Property checks: seeded cases, shrunk counterexamples in plain words, one-line replay.

The cases are drawn here, in the grading process; each case is one probe into the student's worker. They
are drawn from the check's input domains (grader/domains.py: bounds, zero, tiny values and +-pi first)
with a `random.Random` seeded from the grading seed and the check id, so a regrade with the same seed tries
the same inputs. A passing check never starts Hypothesis, whose engine cost 1.2-1.6 ms of CPU per case
(docs/performance.md). Only when a case fails does Hypothesis search again, with the same seed and the
same number of cases as before this sampler existed, and shrink its failure into the smallest failing
case; should it not find one, the drawn failing case is reported as it is. A failing property reports its
counterexample in the words of the check ("with v = 0.1, w = -2 your vel_r was 1.54, expected 4.13") and
the command that replays exactly that case: `grade week2 --check week2.uni_to_diff.round_trip --case
'v=0.1,w=-2.0'`.
"""

from __future__ import annotations

import json
import random
import zlib
from collections.abc import Callable, Iterable, Mapping
from typing import Any

from grader.batched_cases import run_cases
from grader.checks import Context, Mismatch, Outcome
from grader.domains import Domain
from grader.sandbox.errors import SandboxError, StudentError

Case = Callable[..., None]  # case(ctx, **inputs) -> None, raises Mismatch when the answer is wrong


def format_case(inputs: dict[str, Any]) -> str:
    """`v=0.1,w=-2.0`: exact values, parseable by `parse_case`."""
    return ",".join(f"{k}={json.dumps(v, separators=(',', ':'))}" for k, v in inputs.items())


def parse_case(text: str) -> dict[str, Any]:
    """Parse `v=0.1,w=-2.0` or `ticks=[[1,2],[3,4]]` into a dict; ValueError with the reason."""
    parts, depth, start = [], 0, 0
    for i, ch in enumerate(text):
        depth += ch in "[{"
        depth -= ch in "]}"
        if ch == "," and depth == 0:
            parts.append(text[start:i])
            start = i + 1
    parts.append(text[start:])
    out: dict[str, Any] = {}
    for part in filter(None, (p.strip() for p in parts)):
        key, sep, value = part.partition("=")
        if not sep or not key.strip():
            raise ValueError(f"--case: {part!r} is not name=value")
        try:
            out[key.strip()] = json.loads(value.replace("\u2212", "-"))
        except json.JSONDecodeError:
            raise ValueError(
                f"--case: the value of {key.strip()!r} is not a number or list: {value!r}"
            ) from None
    return out


def _replay(ctx: Context, check_id: str, inputs: dict[str, Any]) -> str:
    return f"{ctx.replay_prefix} --check {check_id} --case '{format_case(inputs)}'".strip()


def _sandbox_words(exc: SandboxError, inputs: dict[str, Any]) -> str:
    where = ", ".join(f"{k} = {v}" for k, v in inputs.items())
    return f"with {where}, your code raised an error: {exc}" if isinstance(exc, StudentError) else str(exc)


def case_seed(ctx: Context, check_id: str) -> int:
    """The seed of a check's cases (drawn ones and Hypothesis's search alike): the grading seed and the id."""
    return zlib.crc32(f"{ctx.seed}:{check_id}".encode())


def run_property(
    ctx: Context,
    check_id: str,
    domains: Mapping[str, Domain],
    case: Case,
    *,
    examples: Iterable[dict[str, Any]] = (),
    max_examples: int = 25,
    passed: str = "holds for every case tried",
) -> Outcome:
    """Check `case` on fixed `examples`, then on `max_examples` seeded cases from `domains`; all-or-nothing.

    With `ctx.case` set (a replay), only that case runs. Student exceptions on an input count as a
    failing case (and are shrunk like any other); a timeout or a dead worker stops the search at once.
    `domains` may also be Hypothesis strategies (then Hypothesis draws every case, as it used to).
    """
    if ctx.case is not None:
        unknown = set(ctx.case) - set(domains)
        missing = set(domains) - set(ctx.case)
        if unknown or missing:
            return Outcome(
                0.0,
                f"--case for {check_id} takes {', '.join(domains)}"
                f" (got {', '.join(ctx.case) or 'nothing'})",
                status="error",
            )
        return _one(ctx, check_id, case, dict(ctx.case), replayed=True)
    fixed = [dict(inputs) for inputs in examples]
    if not all(isinstance(d, Domain) for d in domains.values()):
        found = run_cases(ctx, case, fixed, fresh=len(fixed))
        if found is not None:
            return _example_failed(ctx, check_id, fixed[found[0]], found[1])
        return _search(ctx, check_id, domains, case, max_examples, passed)

    drawn = _draw(ctx, check_id, domains, max_examples)
    found = run_cases(ctx, case, fixed + drawn, fresh=len(fixed))  # the probes of many cases together
    if found is not None and found[0] < len(fixed):
        return _example_failed(ctx, check_id, fixed[found[0]], found[1])
    failing = None if found is None else _drawn_failed(ctx, check_id, drawn[found[0] - len(fixed)], found[1])
    if failing is None:
        return Outcome(1.0, f"{passed} ({max_examples} cases)",
                       {"cases": max_examples, "seed": case_seed(ctx, check_id)})
    if isinstance(failing, Outcome):  # a timeout or a dead worker: no search on a worker that hangs
        return failing
    inputs, words = failing
    strategies = {name: d.strategy() for name, d in domains.items()}
    shrunk = _search(ctx, check_id, strategies, case, max_examples, passed)
    if shrunk.fraction < 1.0:
        return shrunk
    return _failed(ctx, check_id, words, inputs)  # Hypothesis's search missed it: the drawn case as it is


def _draw(ctx: Context, check_id: str, domains: Mapping[str, Domain],
          max_examples: int) -> list[dict[str, Any]]:
    """The drawn cases: the simplest first, as Hypothesis does; then both ends; then seeded draws."""
    rng = random.Random(case_seed(ctx, check_id))
    fixed = ("simplest", "low", "high")
    cases = []
    for k in range(max_examples):
        if k < len(fixed):
            cases.append({name: getattr(d, fixed[k])() for name, d in domains.items()})
        else:
            cases.append({name: d.draw(rng) for name, d in domains.items()})
    return cases


def _drawn_failed(ctx: Context, check_id: str, inputs: dict[str, Any],
                  exc: BaseException) -> tuple[dict[str, Any], str] | Outcome:
    """A drawn case that failed: (inputs, words) for a wrong answer or a student exception (Hypothesis
    then searches), or the Outcome of a timeout or dead worker (no search on a worker that hangs)."""
    if isinstance(exc, StudentError):
        return inputs, _sandbox_words(exc, inputs)
    if isinstance(exc, SandboxError):
        return _fatal(ctx, check_id, exc, inputs)
    return inputs, str(exc)


def _search(ctx: Context, check_id: str, strategies: Mapping[str, Any], case: Case, max_examples: int,
            passed: str) -> Outcome:
    """Hypothesis's seeded search over `strategies`, shrinking the failure it finds."""
    from hypothesis import HealthCheck, Phase, Verbosity, given, seed, settings
    from hypothesis.errors import HypothesisException
    from hypothesis.reporting import with_reporter

    state: dict[str, Any] = {"last": None, "fatal": None, "tried": 0}

    def test(**inputs: Any) -> None:
        if state["fatal"] is not None:
            raise Mismatch(str(state["fatal"]))
        state["tried"] += 1
        try:
            case(ctx, **inputs)
        except Mismatch:
            state["last"] = inputs
            raise
        except StudentError as exc:
            state["last"] = inputs
            raise Mismatch(_sandbox_words(exc, inputs)) from None
        except SandboxError as exc:  # timeout, dead worker: stop trying, keep the reason
            state["fatal"] = exc
            state["last"] = inputs
            raise Mismatch(str(exc)) from None

    runner = settings(
        max_examples=max_examples,
        deadline=None,
        database=None,
        derandomize=False,
        suppress_health_check=list(HealthCheck),
        report_multiple_bugs=False,
        print_blob=False,
        verbosity=Verbosity.quiet,
        phases=(Phase.explicit, Phase.generate, Phase.shrink),
    )(seed(case_seed(ctx, check_id))(given(**strategies)(test)))
    try:
        with with_reporter(lambda _text: None):
            runner()
    except Mismatch as exc:
        if state["fatal"] is not None:
            return _fatal(ctx, check_id, state["fatal"], state["last"])
        return _failed(ctx, check_id, str(exc), state["last"])
    except HypothesisException as exc:  # e.g. a flaky answer: the same input passed once and failed once
        if state["fatal"] is not None:  # a timeout mid-search can look flaky to Hypothesis: say what it was
            return _fatal(ctx, check_id, state["fatal"], state["last"])
        return Outcome(
            0.0,
            f"your code gave different answers to the same input ({type(exc).__name__})",
            {"case": state["last"]},
        )
    return Outcome(1.0, f"{passed} ({state['tried']} cases)", {"cases": state["tried"]})


def _one(ctx: Context, check_id: str, case: Case, inputs: dict[str, Any], replayed: bool = False) -> Outcome:
    """One case. A replay (`replayed`) also keeps the traceback of the student's code and a snippet that
    calls their function with these inputs (grader/replay.py)."""
    from grader.replay import snippet

    ctx.last_probe = None
    try:
        case(ctx, **inputs)
    except (Mismatch, SandboxError) as exc:
        found = _example_failed(ctx, check_id, inputs, exc)
    else:
        return Outcome(1.0, "this case passes" if replayed else "", {"case": inputs})
    if replayed:
        code = snippet(ctx.submission, ctx.last_probe)
        if code:
            found.details["snippet"] = code
    return found


def _example_failed(ctx: Context, check_id: str, inputs: dict[str, Any], exc: BaseException) -> Outcome:
    """The outcome of one given case (a fixed example or a replay) that raised `exc`: no search."""
    if isinstance(exc, StudentError):
        from grader.replay import traceback_text

        found = _failed(ctx, check_id, _sandbox_words(exc, inputs), inputs)
        found.details["traceback"] = traceback_text(exc)
    elif isinstance(exc, SandboxError):  # a timeout or a dead worker on this case: say so, and the replay
        from grader.checks import sandbox_message

        status, message = sandbox_message(exc)
        found = _failed(ctx, check_id, message, inputs)
        found.status = status
    else:
        found = _failed(ctx, check_id, str(exc), inputs)
    return found


def _fatal(ctx: Context, check_id: str, exc: SandboxError, inputs: dict[str, Any] | None) -> Outcome:
    """A timeout or dead worker stopped the search: its message, and the replay line of that input."""
    from grader.checks import sandbox_message

    status, message = sandbox_message(exc)
    found = _failed(ctx, check_id, message, inputs)
    found.status = status
    if inputs is not None:
        found.details["case"] = inputs
    return found


def _failed(ctx: Context, check_id: str, words: str, inputs: dict[str, Any] | None) -> Outcome:
    details: dict[str, Any] = {}
    if inputs is not None:
        details = {"counterexample": inputs, "replay": _replay(ctx, check_id, inputs)}
    return Outcome(0.0, words, details)
