"""Imports nothing of the package."""

LIMIT = 3
