"""grader: the isolated autograder of the simiam course (see docs/design.md)."""

import simiam  # noqa: F401  -- first, so simiam.numerics pins the numeric environment before numpy loads
