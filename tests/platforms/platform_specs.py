"""The results formats the platforms document, as validators the bundle tests hold each results.json to.

Gradescope: https://gradescope-autograders.readthedocs.io/en/latest/specs/ ("Output format", "Controlling
Test Case Visibility", "Test case status", "Output String Formatting").
PrairieLearn: https://prairielearn.readthedocs.io/en/latest/externalGrading/ ("Grading results").
Each returns the list of violations (empty when the file follows the spec).
"""

from __future__ import annotations

import json
import math

GS_TOP = {"score", "execution_time", "output", "output_format", "test_output_format", "test_name_format",
          "visibility", "stdout_visibility", "extra_data", "tests", "leaderboard"}
GS_TEST = {"score", "max_score", "status", "name", "name_format", "number", "output", "output_format", "tags",
           "visibility", "extra_data"}
GS_VISIBILITY = {"hidden", "after_due_date", "after_published", "visible"}
GS_FORMATS = {"text", "simple_format", "html", "md", "ansi"}
PL_TEST = {"name", "description", "points", "max_points", "message", "output", "images"}
PL_LIMIT = 1_000_000


def _number(value: object) -> bool:
    return type(value) in (int, float) and math.isfinite(value)


def gradescope_violations(data: object) -> list[str]:
    """What in a parsed results.json breaks Gradescope's autograder specification."""
    if not isinstance(data, dict):
        return ["results.json is not a JSON object"]
    bad = [f"unknown top-level key {k!r}" for k in data if k not in GS_TOP]
    for key in ("visibility", "stdout_visibility"):
        if key in data and data[key] not in GS_VISIBILITY:
            bad.append(f"{key} {data[key]!r} is not one of {sorted(GS_VISIBILITY)}")
    for key in ("output_format", "test_output_format", "test_name_format"):
        if key in data and data[key] not in GS_FORMATS:
            bad.append(f"{key} {data[key]!r} is not a format")
    if "output" in data and not isinstance(data["output"], str):
        bad.append("output must be a string")
    if "execution_time" in data and not _number(data["execution_time"]):
        bad.append("execution_time must be a number of seconds")
    if "extra_data" in data and not isinstance(data["extra_data"], dict):
        bad.append("extra_data must be an object")
    tests = data.get("tests", [])
    if not isinstance(tests, list):
        return bad + ["tests must be a list"]
    if "score" in data:
        if not _number(data["score"]):
            bad.append("score must be a finite number")
    elif not tests or not all(isinstance(t, dict) and "score" in t for t in tests):
        bad.append("score is required at the top level unless every test has one")
    for i, test in enumerate(tests):
        if not isinstance(test, dict):
            bad.append(f"tests[{i}] is not an object")
            continue
        bad += [f"tests[{i}]: unknown key {k!r}" for k in test if k not in GS_TEST]
        for key in ("score", "max_score"):
            if key in test and not _number(test[key]):
                bad.append(f"tests[{i}].{key} must be a finite number")
        if "status" in test and test["status"] not in ("passed", "failed"):
            bad.append(f"tests[{i}].status {test['status']!r} is not passed/failed")
        if "visibility" in test and test["visibility"] not in GS_VISIBILITY:
            bad.append(f"tests[{i}].visibility {test['visibility']!r} is not allowed")
        for key in ("output_format", "name_format"):
            if key in test and test[key] not in GS_FORMATS:
                bad.append(f"tests[{i}].{key} {test[key]!r} is not a format")
        for key in ("name", "output"):
            if key in test and not isinstance(test[key], str):
                bad.append(f"tests[{i}].{key} must be a string")
    if "score" in data and _number(data["score"]) and tests and all(_number(t.get("score")) for t in tests):
        if abs(sum(t["score"] for t in tests) - data["score"]) > 1e-6:
            bad.append("score differs from the sum of the tests' scores")
    return bad


def prairielearn_violations(text: str) -> list[str]:
    """What in a results.json text breaks PrairieLearn's external grading results format."""
    if len(text.encode()) > PL_LIMIT:
        return [f"results.json is {len(text.encode())} bytes, over PrairieLearn's 1 MB"]
    try:
        data = json.loads(text)
    except ValueError as exc:
        return [f"not JSON: {exc}"]
    if not isinstance(data, dict):
        return ["results.json is not a JSON object"]
    gradable = data.get("gradable", True)
    if not isinstance(gradable, bool):
        return ["gradable must be true or false"]
    if not gradable:
        errors = data.get("format_errors")
        ok = isinstance(errors, str) or (isinstance(errors, list) and all(isinstance(e, str) for e in errors))
        return [] if ok and errors else ["a not-gradable result needs format_errors (a string or strings)"]
    bad = []
    score = data.get("score")
    if not _number(score) or not 0.0 <= score <= 1.0:
        bad.append(f"score {score!r} must be a number in [0, 1]")
    for key in ("message", "output"):
        if key in data and not isinstance(data[key], str):
            bad.append(f"{key} must be a string")
    for i, test in enumerate(data.get("tests", [])):
        if not isinstance(test, dict):
            bad.append(f"tests[{i}] is not an object")
            continue
        bad += [f"tests[{i}]: unknown key {k!r}" for k in test if k not in PL_TEST]
        if not isinstance(test.get("name"), str):
            bad.append(f"tests[{i}].name must be a string")
        for key in ("points", "max_points"):
            if not _number(test.get(key)):
                bad.append(f"tests[{i}].{key} must be a finite number")
        if _number(test.get("points")) and _number(test.get("max_points")) \
                and not 0 <= test["points"] <= test["max_points"]:
            bad.append(f"tests[{i}]: points outside [0, max_points]")
        for key in ("message", "output", "description"):
            if key in test and not isinstance(test[key], str):
                bad.append(f"tests[{i}].{key} must be a string")
    return bad
