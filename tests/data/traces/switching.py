"""A week-5-like run of the real simulator for the viewer and report tests: a trusted brain that switches
go_to_goal -> follow_wall -> stop and reports signals of every kind (heading, vectors, label, count,
event, distance). `switching_trace(states)` can rename the states (hostile names for escaping tests)."""

from __future__ import annotations

import math

from simiam.course.weeks import spec_for_week
from simiam.simulator import Simulator
from simiam.world import load_world

SIGNALS = ("theta_g", "u_gtg", "u_ao", "fw_direction", "switches", "at_goal", "d_prog")
STATES = ("go_to_goal", "follow_wall", "stop")


class Switching:
    """The first state for 1 s, the second until 2 s, then the third; u_gtg and u_ao fixed vectors."""

    def __init__(self, states=STATES):
        self.states, self.state, self.switches = states, states[0], 0

    def step(self, readings):
        t = readings["t"]
        state = self.states[0] if t < 1.0 else self.states[1] if t < 2.0 else self.states[2]
        if state != self.state:
            self.state, self.switches = state, self.switches + 1
        return {"vel_r": 3.0, "vel_l": 2.0, "estimate": None, "state": state,
                "debug": {"theta_g": math.pi / 4, "u_gtg": [0.3, 0.3], "u_ao": [-0.2, 0.1],
                          "fw_direction": "left" if state == self.states[1] else None,
                          "switches": self.switches, "at_goal": state == self.states[2], "d_prog": 3.0 - t}}


def switching_trace(states=STATES) -> dict:
    """Three seconds at dt 0.05 in the week-3 world (61 rows), as trace JSON."""
    sim = Simulator(load_world("week3"), Switching(states), spec_for_week(4), dt=0.05, signals=SIGNALS)
    return sim.run(seconds=3.0).to_json()
