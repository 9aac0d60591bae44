"""Instructor tooling for releasing and grading the weeks on the platforms courses already use.

    grade handout week3 --out release/                     # what students download: week3/ and week3.zip
    grade package gradescope week3 --out autograder.zip    # a Gradescope autograder zip
    grade package prairielearn week3 --out pl/week3        # a PrairieLearn externally graded question
    grade package coursera week3 --out coursera/week3      # a Coursera custom grader's build folder
    grade selfcheck                                        # the course's own solutions, stubs, wrong versions

Everything here runs from the instructor's checkout (it reads solutions/). What the platforms run at grading
time (grader.platforms.gradescope / prairielearn / coursera `run`) needs only the installed package plus the
secret file baked into the bundle. See docs/platforms.md.
"""
