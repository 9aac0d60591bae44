"""The worker applies its kernel limits to itself, before any student code (grader.sandbox.limits.Limits
describes them on the grader side and sends them in the worker's config)."""

from __future__ import annotations


def apply_rlimits(spec: dict | None) -> list[str] | None:
    """Set the kernel limits described by `Limits.for_worker` on this process (inherited by children).

    Returns the names of the limits the system refused (macOS, for one, may refuse RLIMIT_AS), or None
    when nothing could be set: no `resource` module (Windows) or no limits sent by the grader
    (grader.sandbox.capabilities). Either way the result then says "local check only"."""
    try:
        import resource
    except ImportError:
        return None
    if spec is None:
        return None
    refused: list[str] = []

    def cap(name: str, which: int, value: int) -> None:
        try:
            _soft, hard = resource.getrlimit(which)
            if hard != resource.RLIM_INFINITY:
                value = min(value, hard)
            resource.setrlimit(which, (value, value))
        except (ValueError, OSError):
            refused.append(name)

    cap("core dumps", resource.RLIMIT_CORE, 0)
    # SIGXCPU at the soft limit kills Python; the hard limit one second later is SIGKILL.
    try:
        _soft, hard = resource.getrlimit(resource.RLIMIT_CPU)
        cpu = int(spec["cpu"])
        hard_cpu = cpu + 1 if hard == resource.RLIM_INFINITY else min(cpu + 1, hard)
        resource.setrlimit(resource.RLIMIT_CPU, (min(cpu, hard_cpu), hard_cpu))
    except (ValueError, OSError):
        refused.append("CPU time")
    cap("memory", resource.RLIMIT_AS, int(spec["memory"]))
    cap("file size", resource.RLIMIT_FSIZE, int(spec["file"]))
    cap("open files", resource.RLIMIT_NOFILE, int(spec["open_files"]))
    if hasattr(resource, "RLIMIT_NPROC"):
        cap("processes", resource.RLIMIT_NPROC, int(spec["processes"]))
    else:
        refused.append("processes")
    return refused
