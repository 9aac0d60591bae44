"""What runs inside the sandbox worker, in the same process as student code (issue 14).

worker (the entry point and its bootstrap), worker_loop (the request loop), probes (the registry of the
small functions called against the loaded submission; each week's in probes_weekN, what they share in
probing), protocol (JSON lines on the private pipes) with caps (field caps), answer_bounds (how large an
answer may be) and shorten (text cut to a length, the one rule set the grader's side cuts with too),
rlimits (the kernel limits the worker sets on itself) and seccomp (its syscall filter).

Nothing here is trusted by the grader, and nothing here may see what the grader trusts: these modules import
only the standard library, numpy (the students' library, preloaded for them), the student-facing modules
grader.sandbox.exposed lists (simiam.control, the week table, the loader, the robot spec) and each other;
never grader.reference, grader.checks, the simulator or its physics, the hidden sets or instructor_tools.
tests/sandbox/test_inside.py walks their imports and fails on anything else. The grading process imports
protocol, caps, answer_bounds, shorten and seccomp from here too (one copy of the wire format, the bounds, the
cut and the filter).
"""
