"""tests/mode_audit.py: without bubblewrap, a skip for want of it must carry the `sandbox` marker."""

from __future__ import annotations

from mode_audit import undeclared_skip


def test_an_undeclared_skip_without_bubblewrap_is_reported() -> None:
    problem = undeclared_skip("bubblewrap (bwrap) is not installed", marked_sandbox=False, bwrap_usable=False)
    assert problem is not None and "not marked `sandbox`" in problem and "bwrap) is not installed" in problem


def test_declared_other_and_bubblewrap_runs_pass() -> None:
    cases = {"marked sandbox": ("no bubblewrap here", True, False),
             "another reason": ("needs setpriv to run the entrypoint", False, False),
             "bubblewrap usable": ("holds only inside bubblewrap (documented)", False, True)}
    found = {name: undeclared_skip(*args) for name, args in cases.items()}
    assert found == dict.fromkeys(cases), found
