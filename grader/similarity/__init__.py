"""Similarity of the students' code blocks (``grade similarity``): winnowed fingerprints of normalised
Python tokens, as MOSS does, over the code blocks only (the handout's text taken out).

``submitted`` (what of a submission is compared), ``tokens`` (normalised tokens), ``fingerprints``
(k-grams and winnowing), ``compare`` (pairs and scores), ``page`` (similarity.html/.json, the printed
list), ``command`` (the command line). docs/batch.md says how to use it and what it cannot do.
"""
