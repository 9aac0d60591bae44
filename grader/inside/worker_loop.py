"""The request loop inside the worker: dispatch ops to the loaded submission and answer in JSON.

Imported by worker.py after the bootstrap has dropped privileges and set the limits. Everything here runs
in the same process as student code, so nothing here is trusted by the grader: it only makes honest
answers convenient (JSON conversion, file and line of an exception). The grader validates every value.
"""

from __future__ import annotations

import faulthandler
import importlib
import inspect
import os
import signal
import sys
import threading
import traceback
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from grader.inside.answer_bounds import MAX_ANSWER_BYTES, OutOfBounds, weigh
from grader.inside.protocol import (
    REQUEST,
    FrameReader,
    NotJSON,
    ProtocolError,
    Record,
    decode_request,
    encode,
    to_json,
)
from grader.inside.step_record import StepLayout, layout_for


class _Worker:
    def __init__(self, config: dict) -> None:
        self.folder = Path(config["submission"])
        self.week = int(config["week"])
        self.loader_name = config.get("loader", "simiam.course.loader:load_submission")
        self.probes = importlib.import_module(config.get("probes", "grader.inside.probes"))
        self.allowed = _probe_names(self.probes)
        self.sub: Any = None
        self.brain: Any = None  # the trusted framework was imported by the bootstrap (worker.py)
        self.layout: StepLayout | None = None  # the step records of the brain's run, when agreed
        self.write: Callable[[int], bytes | dict] | None = None  # the layout's writer for this brain

    def submission(self) -> Any:
        if self.sub is None:
            module, _, func = self.loader_name.partition(":")
            load = getattr(importlib.import_module(module), func)
            self.sub = load(self.folder, self.week)
        return self.sub

    # ---- ops -------------------------------------------------------------------------------------
    def op_ping(self, request: dict) -> Any:
        return None

    def op_load(self, request: dict) -> Any:
        sub = self.submission()
        modules = {name: sorted(k for k in vars(m) if not k.startswith("_"))[:200]
                   for name, m in getattr(sub, "modules", {}).items()}
        errors = [e.to_json() if hasattr(e, "to_json") else {"file": None, "line": None, "message": str(e)}
                  for e in getattr(sub, "errors", [])]
        return {"modules": modules, "errors": errors}

    def op_probe(self, request: dict) -> Any:
        name = request.get("name")
        if name not in self.allowed:
            raise LookupError(f"no probe named {name!r}")
        args = request.get("args") or {}
        return getattr(self.probes, name)(self.submission(), **args)

    def op_brain_start(self, request: dict) -> Any:
        from simiam.control.local_brain import LocalBrain
        from simiam.course.weeks import get_week

        self.brain = self.layout = self.write = None
        _join_core(request.get("cpu"))
        self.brain = LocalBrain(self.submission(), get_week(self.week), request.get("settings") or None,
                                start=_pose(request.get("start")))
        self.layout = _agreed(request.get("record"), self.brain)
        if self.layout is None:
            return None
        self.write = self.layout.writer(self.brain)
        return {"record": True}

    def op_brain_step(self, request: dict) -> Any:
        if self.brain is None:
            raise RuntimeError("brain_step before brain_start")
        return self.brain.step(request["readings"])

    # ---- framing ---------------------------------------------------------------------------------
    def answers(self, request: dict) -> Iterator[dict]:
        """The response(s) to one request: one, except for `probe_many`, which runs its probes in order and
        answers each on its own as soon as it is done, with the ids id, id + 1, ... (the grader reserved
        them), so a probe that hangs or kills this process leaves the answers before it with the grader."""
        if request.get("op") != "probe_many":
            yield self.handle(request)
            return
        rid, probes = request.get("id"), request.get("probes")
        if type(rid) is not int or not isinstance(probes, list):
            yield {"id": rid, "ok": False, "error": {"type": "ProtocolError", "message": "bad probe_many"}}
            return
        for offset, probe in enumerate(probes):
            fields = probe if isinstance(probe, dict) else {}
            yield self.handle({"name": fields.get("name"), "args": fields.get("args"), "op": "probe",
                               "id": rid + offset})

    def step(self, kind: int, rid: int, payload: bytes) -> bytes:
        """A step's readings record (kind, id, payload) that came in parts, answered as `answer_step`;
        ProtocolError for a record that is not the readings of this run's layout."""
        if kind != REQUEST or self.layout is None:
            raise ProtocolError("a step record before brain_start agreed on records")
        return self.answer_step(rid, self.layout.decode_readings(payload))

    def answer_step(self, rid: int, readings: dict) -> bytes:
        """Step `rid`'s answer to `readings`: a step record, or JSON where the answer is not of the record's
        canonical types or the student's code raised (grader.inside.step_record)."""
        write, brain = self.write, self.brain
        if write is None or brain is None:
            raise ProtocolError("a step record before brain_start agreed on records")
        try:  # LocalBrain.step, its answer written as the record (grader.inside.record_writer)
            brain.think(readings)
            answer = write(rid)
        except BaseException as exc:  # noqa: BLE001 - as handle()
            return _encoded({"id": rid, "ok": False, "error": self.describe(exc)})
        if type(answer) is bytes:
            return answer
        response = self.respond(rid, lambda: answer)  # not a record's types: exactly as before records
        try:
            return _encoded(response)
        except (ValueError, TypeError):
            return _encoded({"id": rid, "ok": False,
                             "error": {"type": "NotJSON", "message": "the answer could not be encoded"}})

    def handle(self, request: dict) -> dict:
        rid = request.get("id")
        op = getattr(self, f"op_{request.get('op')}", None)
        if op is None:
            return {"id": rid, "ok": False, "error": {"type": "ProtocolError",
                                                     "message": f"unknown op {request.get('op')!r}"}}
        return self.respond(rid, lambda: op(request))

    def respond(self, rid: Any, compute: Callable[[], Any]) -> dict:
        """The response carrying what `compute()` returns as JSON, or the error it raised, in words."""
        try:
            value = to_json(compute())
            weigh(value)  # the grader takes nothing larger: say so here, in words, rather than be killed
        except NotJSON as exc:
            return {"id": rid, "ok": False, "error": {"type": "NotJSON", "message": str(exc)}}
        except OutOfBounds as exc:
            return {"id": rid, "ok": False, "error": {"type": "TooLarge", "message": str(exc)}}
        except BaseException as exc:  # noqa: BLE001 - SystemExit, KeyboardInterrupt and custom ones too
            return {"id": rid, "ok": False, "error": self.describe(exc)}
        return {"id": rid, "ok": True, "value": value}

    def describe(self, exc: BaseException) -> dict:
        file, line = None, None
        folder = str(self.folder.resolve())
        frames = []  # the traceback through the student's files only, for the replay of a failing case
        for frame in traceback.extract_tb(exc.__traceback__):
            if os.path.dirname(os.path.abspath(frame.filename)) == folder:
                file, line = os.path.basename(frame.filename), frame.lineno
                frames.append({"file": file[:100], "line": line, "function": frame.name[:100],
                               "code": (frame.line or "")[:200]})
        try:
            message = str(exc)
        except BaseException:  # noqa: BLE001 - a student __str__ may raise anything
            message = ""
        if isinstance(exc, SystemExit):
            message = f"your code called sys.exit({message})"
        return {"type": type(exc).__name__[:100], "message": message[:1000], "file": file, "line": line,
                "frames": frames[-20:]}


def _agreed(record: object, brain: Any) -> StepLayout | None:
    """The step records the grader proposed in brain_start, if they are exactly this brain's signals and
    IR count (else the run's steps stay JSON)."""
    if not isinstance(record, dict):
        return None
    names, n_ir = record.get("signals"), record.get("n_ir")
    if names != [s.name for s in brain.signals] or type(n_ir) is not int or n_ir != brain._n_ir:
        return None
    return layout_for(names, n_ir)


def _pose(value: object) -> tuple[float, float, float] | None:
    """The start pose the grader sent with brain_start: three finite numbers, else None (the week's)."""
    import math

    if not isinstance(value, list) or len(value) != 3:
        return None
    if not all(type(c) in (int, float) and math.isfinite(c) for c in value):
        return None
    return float(value[0]), float(value[1]), float(value[2])


def _join_core(cpu: object) -> None:
    """Keep this thread on `cpu`, the core the grading thread keeps to for a scenario run (the two take
    turns: grader.sandbox.same_core says why), where the system lets it; only speed depends on it."""
    put = getattr(os, "sched_setaffinity", None)
    if type(cpu) is int and put is not None:
        try:
            put(0, {cpu})
        except (OSError, ValueError, OverflowError):
            pass


def _probe_names(module: Any) -> frozenset[str]:
    """Allow-list: the module's __all__, else its public functions defined in it."""
    names = getattr(module, "__all__", None)
    if names is None:
        names = [n for n, f in vars(module).items()
                 if not n.startswith("_") and inspect.isfunction(f) and f.__module__ == module.__name__]
    return frozenset(names)


def numerics_report() -> object:
    """The numeric environment this worker's numpy loaded with (simiam.numerics), or why it is unknown.
    Read in the bootstrap, before the uid drop (it reads /proc and may import codecs the dropped uid
    cannot read) and before any student code; sent in the ready message."""
    try:
        from simiam.numerics import describe

        return describe()
    except Exception as exc:  # reported as "not official"; grading goes on
        return {"official": False, "note": f"could not read the numeric environment: {type(exc).__name__}"}


def serve(config: dict) -> None:
    """Announce readiness, then answer requests until the grader closes the pipe.

    Before any student code runs, SIGUSR1 is set to make faulthandler dump every thread's stack on the
    grader's dump pipe: the grader sends it when a call times out, to say where the code was stuck. The
    readiness message carries this process's pid and serving thread, which the grader uses to find and read
    that dump (it is sent before student code, so the student cannot forge it).
    """
    fd_in, fd_out = int(config["fd_in"]), int(config["fd_out"])
    if config.get("fd_dump") is not None and hasattr(signal, "SIGUSR1"):  # Windows has neither
        faulthandler.register(signal.SIGUSR1, file=int(config["fd_dump"]), all_threads=True)
    worker = _Worker(config)
    uid = getattr(os, "getuid", lambda: None)()
    _send(fd_out, {"id": 0, "ok": True, "value": {"pid": os.getpid(), "uid": uid,
                                                  "thread": threading.get_ident(),
                                                  "seccomp": bool(config.get("seccomp")),
                                                  "refused_limits": config.get("refused_limits", []),
                                                  "numerics": config.get("numerics")}})
    reader = FrameReader()
    while True:
        try:
            line = reader.pop()
        except ProtocolError:
            return
        if line is None:
            data = os.read(fd_in, 65536)
            if not data:
                return
            layout = worker.layout
            whole = None if layout is None or reader.pending else layout.decode_request(data)
            if whole is not None:  # a step's readings record whole in one read, as nearly all are
                _reply(fd_out, worker.answer_step(*whole))
                continue
            try:
                reader.feed(data)
            except ProtocolError:
                return
            continue
        if isinstance(line, Record):  # a step's record that came in parts
            try:
                answer = worker.step(line.kind, line.rid, line.payload)
            except ProtocolError:
                return
            _reply(fd_out, answer)
            continue
        try:
            request = decode_request(line)
        except ProtocolError:
            return
        for response in worker.answers(request):
            _flush_student_output()
            try:
                _send(fd_out, response)
            except (ValueError, TypeError):
                _send(fd_out, {"id": response.get("id"), "ok": False,
                               "error": {"type": "NotJSON", "message": "the answer could not be encoded"}})


def _reply(fd_out: int, answer: bytes) -> None:
    """Send a step's answer, after what the student printed while computing it."""
    _flush_student_output()
    _write_all(fd_out, answer)


def _flush_student_output() -> None:
    """What the student printed reaches the grader's output pipe before the answer it belongs to."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except BaseException:  # noqa: BLE001, S110 - student may have replaced or closed them
            pass


def _send(fd: int, message: dict) -> None:
    _write_all(fd, _encoded(message))


def _encoded(message: dict) -> bytes:
    """`message` as a JSON line, or a TooLarge error in its place; ValueError or TypeError if it has no
    JSON form."""
    data = encode(message)
    if len(data) > MAX_ANSWER_BYTES:  # within the bounds of values and text, but long numbers or escapes
        too_large = f"a value of {len(data)} bytes as JSON (at most {MAX_ANSWER_BYTES})"
        data = encode({"id": message.get("id"), "ok": False,
                       "error": {"type": "TooLarge", "message": too_large}})
    return data


def _write_all(fd: int, data: bytes) -> None:
    while data:
        written = os.write(fd, data)
        data = data[written:]
