"""The command validation as it was before issue 24's fast paths (simiam/brain.py and the `points` rule of
simiam/signals.py at f3ce8ef), kept to prove that the new one gives the same command, bit for bit, or the
same BrainError, for whatever a brain answers."""
from simiam.brain import STATE_CHARS, BrainError, _estimate
from simiam.signals import _CLEAN, _FLOAT, MAX_POINTS, debug_plan, real


def _points(p, n):
    if not (isinstance(p, (list, tuple)) and len(p) == 2) or n > MAX_POINTS:
        return None
    out = []
    for row in p:
        if not (isinstance(row, (list, tuple)) and len(row) == n):
            return None
        if set(map(type, row)) == _FLOAT:
            total = sum(row)
            if total - total != 0.0:
                return None
            out.append(list(row))
        elif all(real(c) for c in row):
            out.append([float(c) for c in row])
        else:
            return None
    return out


RULES = dict(_CLEAN, points=_points)


def clean_debug(debug, signals, n_ir):
    if not isinstance(debug, dict):
        debug = {}
    get = debug.get
    return {name: RULES[s.kind](get(name), n) for (name, _, n), s in zip(debug_plan(signals, n_ir), signals,
                                                                          strict=True)}


def validate_command(command, signals, n_ir):
    if not isinstance(command, dict):
        raise BrainError(f"the command must be a dict, got {type(command).__name__}")
    out = {}
    for key in ("vel_r", "vel_l"):
        val = command.get(key)
        if not real(val):
            raise BrainError(f"{key} must be a finite number (rad/s), got {val!r:.60}")
        out[key] = float(val)
    est = command.get("estimate")
    if type(est) is list and len(est) == 3 and set(map(type, est)) == _FLOAT:
        total = est[0] + est[1] + est[2]
        est = list(est) if total - total == 0.0 else _estimate(est)
    elif est is not None:
        est = _estimate(est)
    out["estimate"] = est
    state = command.get("state")
    if state is not None and not isinstance(state, str):
        raise BrainError(f"state must be a string, got {type(state).__name__}")
    out["state"] = None if state is None else state[:STATE_CHARS]
    out["debug"] = clean_debug(command.get("debug"), signals, n_ir)
    return out
