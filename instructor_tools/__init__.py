"""Instructor tooling that must never reach students: it lives in the course checkout only and is left
out of the wheel (pyproject.toml packages only simiam and grader; tests/packaging proves it).

- `reference_brains`: complete reference controllers (go-to-goal, avoid-obstacles) used by `simiam bench`,
  the fleet and the closed-loop fidelity cross-checks;
- `reference_week5`: the week-5 reference brain (the sp14 blend and the author's switching, bit-exact with
  the recordings), which cross-checks solutions/week5 on the recorded goals the golden files hold back;
- `reference_week7`: the week-7 reference brain (the author's navigation automaton on the week-5/6
  references, sigma by the recorded LU), bit-exact with the recordings; solutions/week7 must command the
  same wheel speeds on every recorded goal and every hidden variant (tests/fidelity/test_week7_reference.py);
- `hidden/weekN.json`: the hidden scenario variants of official grading (`grade --hidden`, batch), each
  validated against the reference solution by tests/grader/test_hidden.py (week 5: test_hidden_week5.py,
  week 7: test_hidden_week7.py); `hidden_week6` and `hidden_week7` make weeks 6 and 7's with margins;
- `kernels`: the BLAS kernels this CPU runs, grouped by what OpenBLAS really loads, for the hidden-set
  makers and tests/grader/test_verdict_margins.py (verdicts identical under every kernel).

Importable with the repository root on sys.path (`python -m pytest` from the checkout); the console
scripts of an editable install reach it through `simiam.course.folders.instructor_tool`.
"""
