"""The isolation layer: student code runs only in a sandboxed worker process and can never forge its grade.

    from grader.sandbox import StudentSession, RemoteBrain, Limits
    with StudentSession(week, spliced_dir, Limits()) as session:    # sandbox="auto" | "bwrap" | "subprocess"
        session.load(); session.call("probe", name=..., args={...}); session.isolation_note

Modules (the grader's side; what runs inside the worker is the package grader.inside): isolation
(bubblewrap or plain subprocess, dedicated uid), exposed (what the worker can import), capabilities (what
this system offers), runner (start, deadlines, kill the whole tree), channel (the same over standard pipes
and threads, for every worker without bubblewrap: macOS, Windows, Linux without it), output (capped capture of
stdout/stderr), limits (Limits), workdir (private copy of the spliced folder), reach (what the worker's uid
can reach), session (StudentSession, RemoteBrain), validate (type checks on untrusted values), errors, stuck,
leftovers, bench.

What holds in every mode: the grading process never imports student code; only strict JSON crosses back
and the grader validates it; per-call and per-submission wall limits, RLIMIT_CPU/AS/FSIZE/NOFILE/NPROC,
no core dumps; output capped; a clean environment; as root, a dedicated unprivileged uid per worker, so the
process limit binds and every process the student starts (setsid, double fork) is killed by uid.
In every mode the worker imports simiam and grader only from its own library (exposed: the student-facing
framework and the worker's code, no reference implementation of any student block), and its seccomp filter
forbids new processes, so the memory limit is per submission. With bubblewrap in addition: no network, own
PID/IPC/UTS namespaces, private size-capped /tmp, read-only view of only the submission copy, the Python
environment and that library (no solutions/, reference code, hidden checks, output folder or other
submissions), no capabilities. Without parts of this (capabilities), results say "local check only".
"""

from grader.sandbox.errors import SandboxError, SandboxUnavailable, StudentError, StudentTimeout, WorkerDied
from grader.sandbox.limits import Limits


def __getattr__(name: str):
    # Lazy: importing Limits or the errors does not load the grader-side session machinery.
    if name in ("RemoteBrain", "StudentSession"):
        from grader.sandbox import session

        return getattr(session, name)
    raise AttributeError(name)


__all__ = ["Limits", "RemoteBrain", "SandboxError", "SandboxUnavailable", "StudentError", "StudentSession",
           "StudentTimeout", "WorkerDied"]
