#!/usr/bin/env bash
# Gradescope runs this once, as root, while it builds the autograder image (working folder /autograder).
# It installs Python, bubblewrap where the image allows, and the grader from the wheel in this bundle,
# then closes the bundle's secret (seed and hidden variant set) to every user but root.
#
# For a trial outside Gradescope every path can be moved: AUTOGRADER_ROOT (default /autograder),
# SIMIAM_VENV (default /opt/simiam-venv), SIMIAM_PYTHON (default python3), SIMIAM_SKIP_APT=1.
set -euo pipefail

ROOT="${AUTOGRADER_ROOT:-/autograder}"
SOURCE="$ROOT/source"
VENV="${SIMIAM_VENV:-/opt/simiam-venv}"
PYTHON="${SIMIAM_PYTHON:-python3}"

if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1 && [ "${SIMIAM_SKIP_APT:-0}" != 1 ]; then
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -q
    apt-get install -y -q --no-install-recommends python3 python3-venv python3-pip
    # bubblewrap is the sandbox; some images forbid the namespaces it needs, and grading then says so
    apt-get install -y -q --no-install-recommends bubblewrap || echo "setup: bubblewrap not installed"
fi

"$PYTHON" -c 'import sys; sys.exit(sys.version_info < (3, 10))' \
    || { echo "setup: the grader needs Python 3.10 or newer; $PYTHON is $("$PYTHON" -V 2>&1)" >&2; exit 1; }

"$PYTHON" -m venv "$VENV"
"$VENV/bin/python" -m pip install --quiet --disable-pip-version-check "$SOURCE"/dist/simiam-*.whl

if [ "$(id -u)" = 0 ]; then chown -R root:root "$SOURCE/secret"; fi
chmod -R go-rwx "$SOURCE/secret"

# the secret is readable by root only, the installed package holds no answers, and which isolation holds
"$VENV/bin/python" -I -m grader.platforms.gradescope check --root "$ROOT"
