"""A fake package whose modules import each other in a circle (test data, never imported)."""
