"""Batch grading of a whole class (``grade weekN --batch DIR``); see docs/batch.md.

runner (the command), submissions and zips (reading the class folder safely), pool and executors (where
grading processes run), grading_process (their side of the pipes), task (the grading function they
run), cache and store (resuming, atomic files), exports, summary and fallback_page (what the instructor
gets), progress (the stderr line).
"""
