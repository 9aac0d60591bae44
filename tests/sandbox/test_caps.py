"""Issue 10 items 4 and 5: every field the worker sends is capped and free of lone surrogates before the
grader stores, prints or repeats it; a result never grows past 2 MB; lone surrogates never crash the
writing of a result or a report."""

from __future__ import annotations

import json
from pathlib import Path

from sandbox_wrong import naive

from grader.grading import write_outputs
from grader.inside import caps
from grader.inside.protocol import decode
from grader.result_size import MAX_RESULT_BYTES, bound_result, result_bytes
from grader.sandbox.session import _check_load, _student_error

MEGA = "<img src=x onerror=alert(1)>" * 40_000          # > 1 MB
FORGED_ERROR = {"type": MEGA, "message": MEGA, "file": MEGA, "line": 10**30}
# (the same string objects repeated: a few MB in memory, hundreds of MB once written out)
FORGED_LOAD = {"modules": {f"m{i}" + MEGA[:1000]: [MEGA[:1000]] * 1000 for i in range(200)},
               "errors": [{"file": MEGA, "line": -1, "message": MEGA}] * 1000}


def text_size(value: object) -> int:
    """Characters of text in a value, counted without serializing it."""
    if isinstance(value, str):
        return len(value)
    if isinstance(value, dict):
        return sum(text_size(k) + text_size(v) for k, v in value.items())
    if isinstance(value, list):
        return sum(text_size(v) for v in value)
    return 0


def test_a_forged_error_is_capped_field_by_field() -> None:
    error = _student_error(FORGED_ERROR)
    assert len(error.message) <= caps.MESSAGE_CHARS and len(error.type_name) <= caps.TYPE_CHARS
    assert len(error.file) <= caps.FILE_CHARS and error.line is None
    assert len(str(error)) < 1500
    assert len(str(naive.student_error_fields(FORGED_ERROR)[2])) > 1_000_000      # the old rebuild kept it


def test_a_forged_load_report_is_capped() -> None:
    load = _check_load(FORGED_LOAD)
    assert len(json.dumps(load)) < 200_000
    assert len(load["modules"]) <= caps.MAX_MODULES and len(load["errors"]) <= caps.MAX_ERRORS
    assert text_size(naive.check_load(FORGED_LOAD)) > 100_000_000


def test_lone_surrogates_from_the_worker_are_replaced() -> None:
    line = json.dumps({"id": 1, "ok": False, "error": {"message": "bad \ud800 text", "\udfff": ["\udc80"]}})
    message = decode(line.encode())
    assert message["error"]["message"] == "bad \ufffd text"
    assert message["error"]["\ufffd"] == ["\ufffd"]
    json.dumps(message, ensure_ascii=False).encode("utf-8")        # strict UTF-8 now works
    assert "\ud800" in naive.decode(line.encode())["error"]["message"]   # plain json.loads keeps it


def test_a_result_with_lone_surrogates_is_written(tmp_path: Path) -> None:
    result = {"week": 2, "score": 0.0, "max_score": 1.0, "status": "graded", "seed": 1, "grader_version": "x",
              "submission": "caf\udce9", "message": "\ud800",
              "checks": [{"id": "week2.x", "name": "\ud800", "kind": "property", "visibility": "visible",
                          "points": 0.0, "max_points": 1.0, "status": "failed", "message": "a \udfff b",
                          "details": {}}]}
    json_path, html_path = write_outputs(result, {}, tmp_path)
    assert json.loads(json_path.read_text())["checks"][0]["message"] == "a \udfff b"
    html = html_path.read_text(encoding="utf-8")           # strict UTF-8: the surrogate did not reach it
    assert "a \\udfff b" in html                             # shown as a visible escape (grader.untrusted)


def test_a_result_stays_under_2_mb_whatever_it_holds() -> None:
    checks = [{"id": f"week3.c{i}", "name": MEGA, "kind": "property", "points": 1.0, "max_points": 1.0,
               "status": "passed", "message": MEGA,
               "details": {"v": list(range(100_000)), "deep": [[[MEGA]]]}}
              for i in range(12)]
    result = {"week": 3, "score": 12.0, "max_score": 12.0, "status": "graded", "checks": checks,
              "student_output": MEGA}
    bounded = bound_result(result)
    assert result_bytes(bounded) <= MAX_RESULT_BYTES < result_bytes(result)
    assert bounded["score"] == 12.0 and [c["points"] for c in bounded["checks"]] == [1.0] * 12
    assert [c["id"] for c in bounded["checks"]] == [c["id"] for c in checks] and "truncated" in bounded
    small = {"week": 3, "score": 1.0, "checks": [{"id": "a", "message": "ok"}]}
    assert bound_result(small) is small
