"""kill_uid's helper as it was before: the first `kill` on root's PATH, even in a folder only root can enter
(a PATH entry under /root, or a folder of links hiding bwrap), which the dedicated uid cannot exec: the
grading died with PermissionError in every subprocess-mode session that started a worker."""

from __future__ import annotations

import shutil


def kill_helper() -> list[str]:
    """The old choice, in place of grader.sandbox.runner._kill_helper."""
    return [shutil.which("kill") or "/bin/kill", "-KILL", "-1"]
