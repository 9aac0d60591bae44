# WRONG VERSION kept for tests/packaging/test_answer_search.py: uni_to_diff rearranged algebraically and
# renamed (no line and no expression shape in common with the solution; the same values).
def wheels_for(radius, base, speed, turn):
    half = turn * base / 2
    return (speed + half) / radius, (speed - half) / radius
