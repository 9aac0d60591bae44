#!/bin/sh
# PrairieLearn's entrypoint for the simiam grader: grades /grade/student, writes /grade/results/results.json.
# Usage (info.json's entrypoint): simiam-pl-grade /grade/serverFilesCourse/simiam_weekN   (the secret)
# GRADE_ROOT, SIMIAM_HOME (default /opt/simiam) and SIMIAM_VENV (default /opt/simiam-venv) move the paths.
GRADE_ROOT="${GRADE_ROOT:-/grade}"
SIMIAM_HOME="${SIMIAM_HOME:-/opt/simiam}"
SIMIAM_VENV="${SIMIAM_VENV:-/opt/simiam-venv}"
mkdir -p "$GRADE_ROOT/results"
SECRET="${1:-$GRADE_ROOT/serverFilesCourse/simiam}"
"$SIMIAM_VENV/bin/python" -I -m grader.platforms.prairielearn run --root "$GRADE_ROOT" --home "$SIMIAM_HOME" \
    --secret "$SECRET"
status=$?
if [ ! -s "$GRADE_ROOT/results/results.json" ]; then
    printf '{"gradable": false, "format_errors": ["The grader itself failed (exit status %s), not because of your code; your instructor will look into it."]}\n' "$status" > "$GRADE_ROOT/results/results.json"
fi
exit 0
