"""Wrong versions of the sandbox's trust-critical helpers; the unit tests prove they would be caught."""
