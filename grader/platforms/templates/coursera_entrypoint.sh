#!/bin/sh
# Coursera's entrypoint (custom grader v2) for the simiam grader of one week: grades /shared/submission and
# writes /shared/feedback.json and /shared/htmlFeedback.html. Coursera passes the part in $partId and drops
# the environment the Dockerfile sets, so the paths are set here; COURSERA_SHARED (default /shared),
# SIMIAM_HOME (default /opt/simiam) and SIMIAM_VENV (default /opt/simiam-venv) move them for a trial.
SHARED="${COURSERA_SHARED:-/shared}"
SIMIAM_HOME="${SIMIAM_HOME:-/opt/simiam}"
SIMIAM_VENV="${SIMIAM_VENV:-/opt/simiam-venv}"
# learners see only the feedback files; the grader's log goes to stderr, which course staff see
"$SIMIAM_VENV/bin/python" -I -m grader.platforms.coursera run --shared "$SHARED" --home "$SIMIAM_HOME" 1>&2
status=$?
if [ ! -s "$SHARED/feedback.json" ]; then
    printf '{"fractionalScore": 0.0, "feedback": "The grader itself failed (exit status %s), not because of your code; your instructor can see why and will regrade."}\n' "$status" > "$SHARED/feedback.json"
fi
exit 0
