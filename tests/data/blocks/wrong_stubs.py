"""Wrong stubs kept as test data: (week, file, text in the generated stub, replacement, what goes wrong).

tests/course/test_stubs_run.py applies each to a copy of assignments/weekN and must catch it.
"""

WRONG_STUBS = [
    # the placeholder forgets vel_l: the first step raises NameError
    (2, "differential_drive.py", "    vel_r = 0\n    vel_l = 0\n", "    vel_r = 0\n", "crash"),
    # a placeholder that makes the week-2 robot move (it should stay still)
    (2, "differential_drive.py", "    vel_l = 0\n", "    vel_r = 1.0\n    vel_l = 1.0\n", "straight"),
    # a week-3 placeholder that turns (the stub robot should drive straight)
    (3, "qb_supervisor.py", "        vel_r = vel_r_d\n", "        vel_r = vel_r_d + 1\n", "turns"),
    # a placeholder whose value breaks the arithmetic after the block: TypeError on the first step
    (4, "avoid_obstacles.py", "        e_k = 0\n", "        e_k = None\n", "crash"),
]
