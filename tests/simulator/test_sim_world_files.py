"""World files: the packaged worlds load, and broken files give a WorldFileError naming the file, the
line, the element and what is wrong (never a raw traceback); a misspelt attribute is one of them."""

from __future__ import annotations

import numpy as np
import pytest
from sim_helpers import DATA, wrong

from simiam.world import World, WorldFileError, load_world

BROKEN = DATA / "worlds"

# file -> words the message must contain (besides the file name)
EXPECTED = {
    "missing_attribute.xml": ["line 8", "<pose>", "missing attribute 'y'"],
    "not_a_number.xml": ["line 12", "<point>", "'zero.2'", "not a number"],
    "two_points.xml": ["line 9", "<geometry>", "2 point", "at least 3"],
    "unknown_element.xml": ["line 10", "<vertex>", "unknown element"],
    "syntax_error.xml": ["line 13", "XML syntax error", "mismatched tag"],
    # a misspelt attribute was ignored (the robot started at theta 0): refused, with the closest names
    "misspelt_attribute.xml": ["line 5", "<pose>", "unknown attribute 'thetaa' (did you mean 'theta'?)",
                               "the attributes of <pose> are, closest first: theta, x, y"],
}


def message_problems(load) -> list:
    out = []
    for name, words in EXPECTED.items():
        try:
            load(BROKEN / name)
        except WorldFileError as e:
            msg = str(e)
            missing = [w for w in [name, *words] if w not in msg]
            if missing or "Traceback" in msg:
                out.append((name, missing))
        except Exception as e:  # anything else is a raw crash for the student
            out.append((name, type(e).__name__))
        else:
            out.append((name, "accepted"))
    return out


def test_broken_world_messages():
    assert message_problems(load_world) == []


def test_naive_loader_is_caught():
    assert message_problems(wrong("naive_world_loader").load_world)


def test_missing_file_and_unknown_name():
    with pytest.raises(WorldFileError, match="no such world file"):
        load_world(BROKEN / "nope.xml")
    with pytest.raises(WorldFileError, match="known: final, week1"):
        load_world("week9")


def test_packaged_worlds():
    counts = {"week1": 4, "week2": 4, "week3": 4, "week4": 6, "week5": 6, "final": 10}
    for name, n in counts.items():
        w = load_world(name)
        assert len(w.obstacles) == n and w.start == (0.0, 0.0, 0.0), name
    assert load_world("final").goal == (1.1, 1.1)
    # week 4's L: x[-0.2, 0.4] x y[0.2, 0.4] and x[-0.4, -0.2] x y[0.2, 0.8]
    l1, l2 = load_world("week4").obstacles[:2]
    def bbox(p):
        xs, ys = [v[0] for v in p], [v[1] for v in p]
        return [min(xs), max(xs), min(ys), max(ys)]
    assert np.allclose(bbox(l1), [-0.2, 0.4, 0.2, 0.4])
    assert np.allclose(bbox(l2), [-0.4, -0.2, 0.2, 0.8], atol=1e-5)
    assert l2[1][0] != -0.2  # theta is the literal 1.5708, not pi/2


def test_world_from_code_rejects_degenerate_polygons():
    with pytest.raises(ValueError, match="at least 3"):
        World("mine", [np.array([[0.0, 0.0], [1.0, 0.0]])])
