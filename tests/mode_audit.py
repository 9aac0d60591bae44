"""The suite's promise for the two isolation modes: a test either holds with and without bubblewrap (the
grader's verdicts are the same in both) or is marked `sandbox` ("needs bubblewrap"). Where bubblewrap cannot
make a sandbox (a machine without it, or .ci/run's second run, bwrap hidden), a test that skips for want of
bubblewrap without that marker is reported as failed: its skip would hide what subprocess mode does to it."""

from __future__ import annotations

import pytest

from grader.sandbox.isolation import bwrap_works  # the real one: some tests patch the module's name

MODE_WORDS = ("bubblewrap", "bwrap")


def undeclared_skip(reason: str, marked_sandbox: bool, bwrap_usable: bool) -> str | None:
    """Why a skip breaks the promise (None when it does not): it names bubblewrap, bubblewrap is unusable
    here, and the test is not marked `sandbox`."""
    if bwrap_usable or marked_sandbox or not any(word in reason.lower() for word in MODE_WORDS):
        return None
    return (f"skipped without bubblewrap ({reason}) but not marked `sandbox`: a test that claims both "
            "isolation modes must hold in subprocess mode too; if it truly needs bubblewrap, mark it "
            "@pytest.mark.sandbox (or give its bubblewrap parameter that mark)")


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo):
    outcome = yield
    report = outcome.get_result()
    if not report.skipped or hasattr(report, "wasxfail"):
        return
    longrepr = report.longrepr
    reason = str(longrepr[2] if isinstance(longrepr, tuple) and len(longrepr) == 3 else longrepr)
    marked = item.get_closest_marker("sandbox") is not None
    problem = undeclared_skip(reason.removeprefix("Skipped: "), marked, bwrap_works()[0])
    if problem:
        report.outcome = "failed"
        report.longrepr = problem
