#!/bin/sh
# PrairieLearn's entrypoint for the simiam grader: grades /grade/student, writes /grade/results/results.json.
# Usage (info.json's entrypoint): simiam-pl-grade /grade/serverFilesCourse/simiam_weekN   (the secret)
# GRADE_ROOT, SIMIAM_HOME (default /opt/simiam) and SIMIAM_VENV (default /opt/simiam-venv) move the paths.
GRADE_ROOT="${GRADE_ROOT:-/grade}"
SIMIAM_HOME="${SIMIAM_HOME:-/opt/simiam}"
SIMIAM_VENV="${SIMIAM_VENV:-/opt/simiam-venv}"
mkdir -p "$GRADE_ROOT/results"
rm -f "$GRADE_ROOT/results/results.json"   # only what this grading writes counts
SECRET="${1:-$GRADE_ROOT/serverFilesCourse/simiam}"
"$SIMIAM_VENV/bin/python" -I -m grader.platforms.prairielearn run --root "$GRADE_ROOT" --home "$SIMIAM_HOME" \
    --secret "$SECRET"
status=$?
if [ "$status" -ne 0 ]; then
    # any non-zero exit is a failure: a results.json there was not written by a finished grading (a killed
    # grader, a forged file), so it is replaced with the failure; if it cannot be, this exits non-zero too
    rm -f "$GRADE_ROOT/results/results.json" || exit 1
    printf '{"gradable": false, "format_errors": ["The grader itself failed, not because of your code (exit status %s); your instructor will look into it."]}\n' "$status" > "$GRADE_ROOT/results/results.json" || exit 1
fi
exit 0
