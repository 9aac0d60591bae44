"""Wrong on purpose: the replay's fast rounding (simiam.viewer.replay._column) without its guard near a
half. The product v * 10**digits is rounded to a float first, so a number just above or below a half in
its last decimal can land on the half, or cross it, and round the other way than round() does (0.00005 is
stored a hair above 5e-5: round() gives 0.0001, this gives 0.0). tests/viewer/test_replay_rounding.py
shows its comparison with round() catches this."""


def column(values: list, digits: int) -> list:
    scale = 10.0 ** digits
    out = []
    for v in values:
        if type(v) is float and -2.0 ** 33 < (y := v * scale) < 2.0 ** 33:
            f = y // 1.0
            r = (f + 1.0 if y - f > 0.5 else f) / scale
            out.append(0.0 if r == 0 else r)
        elif v is None or isinstance(v, bool) or not isinstance(v, (int, float)) or v - v != 0:
            out.append(None)
        else:
            r = round(float(v), digits)
            out.append(0.0 if r == 0 else r)
    return out
