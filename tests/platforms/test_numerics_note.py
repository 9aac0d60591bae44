"""Issue 20: where a platform's CPU could not be given the official numeric environment, the student reads
so on Gradescope and PrairieLearn (the result's `numerics` note); where it was official, nothing is added."""

from __future__ import annotations

from grader.platforms import gradescope, prairielearn

NOTE = ("the BLAS kernel is SkylakeX, not Haswell: runs here can differ from official grading in the last "
        "digits")
RESULT = {"week": 3, "score": 10.0, "max_score": 10.0, "status": "graded", "checks": [],
          "isolation": "bwrap", "isolation_note": "full sandbox"}
CONFIG = {"week": 3, "hidden_checks": 0}


def test_the_note_reaches_gradescope_and_prairielearn_when_not_official() -> None:
    result = dict(RESULT, numerics={"official": False, "kernel": "SkylakeX", "note": NOTE})
    assert f"Numerics: {NOTE}" in gradescope.summary_html(result, CONFIG)
    assert f"numerics: {NOTE}" in prairielearn.results_json(result)["message"]


def test_nothing_is_added_when_official() -> None:
    result = dict(RESULT, numerics={"official": True, "kernel": "Haswell", "note": ""})
    assert "umerics" not in gradescope.summary_html(result, CONFIG)
    assert "umerics" not in prairielearn.results_json(result)["message"]
