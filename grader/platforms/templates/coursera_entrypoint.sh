#!/bin/sh
# Coursera's entrypoint (custom grader v2) for the simiam grader of one week: grades /shared/submission and
# writes /shared/feedback.json and /shared/htmlFeedback.html. Coursera passes the part in $partId and drops
# the environment the Dockerfile sets, so the paths are set here; COURSERA_SHARED (default /shared),
# SIMIAM_HOME (default /opt/simiam) and SIMIAM_VENV (default /opt/simiam-venv) move them for a trial.
SHARED="${COURSERA_SHARED:-/shared}"
SIMIAM_HOME="${SIMIAM_HOME:-/opt/simiam}"
SIMIAM_VENV="${SIMIAM_VENV:-/opt/simiam-venv}"
# only what this grading writes counts: nothing left in /shared before it
rm -f "$SHARED/feedback.json" "$SHARED/htmlFeedback.html"
# learners see only the feedback files; the grader's log goes to stderr, which course staff see
"$SIMIAM_VENV/bin/python" -I -m grader.platforms.coursera run --shared "$SHARED" --home "$SIMIAM_HOME" 1>&2
status=$?
if [ "$status" -ne 0 ]; then
    # any non-zero exit is a failure: whatever feedback is there was not written by a finished grading (a
    # killed grader, a forged file), so it is replaced; if it cannot be, this exits non-zero too
    echo "simiam grader: exit status $status; the feedback says the grading failed" 1>&2
    rm -f "$SHARED/htmlFeedback.html" "$SHARED/feedback.json" || exit 1
    if [ "$status" -eq 3 ]; then
        why="The grader is not set up to run code safely on this grading machine, so your code was not run and nothing was graded; your course staff can see why and will regrade."
    else
        why="The grader itself failed, not because of your code (exit status $status); your instructor can see why and will regrade."
    fi
    printf '{"fractionalScore": 0.0, "feedback": "%s"}\n' "$why" > "$SHARED/feedback.json" || exit 1
fi
exit 0
