"""Wrong: week 3 checks, one sending a probe the sandbox does not have, one naming its probe by a variable."""

from grader.checks import Check, Context, Outcome

FAST = "go_to_goal"


def _heading(ctx: Context) -> float:
    answer = ctx.probe("go_to_goal_fast", gains={"Kp": 1.0}, calls=[])
    return float(answer[0]["theta_g"])


def theta_g(ctx: Context) -> Outcome:
    return Outcome(float(_heading(ctx) == 0.0))


def keeps_w(ctx: Context) -> Outcome:
    return Outcome(float(ctx.probe("ensure_w", v=0.1, w=1.0)[0] > 0))


def by_name(ctx: Context) -> Outcome:
    return Outcome(float(bool(ctx.probe(FAST, gains={}, calls=[]))))


CHECKS = [
    Check("week3.go_to_goal.theta_g", "theta_g", "property", 1.0, theta_g, ("go_to_goal.py",)),
    Check("week3.ensure_w.keeps_w", "ensure_w keeps w", "property", 1.0, keeps_w, ("qb_supervisor.py",)),
    Check("week3.go_to_goal.by_name", "by name", "property", 1.0, by_name, ("go_to_goal.py",)),
]
