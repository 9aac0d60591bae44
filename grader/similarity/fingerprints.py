"""Winnowing (Schleimer, Wilkerson and Aiken 2003, the method of MOSS): a document's fingerprints.

Every run of K consecutive tokens (a k-gram) is hashed; of each WINDOW consecutive hashes the smallest is
kept (the rightmost when tied, and each once). Two texts sharing a run of at least K + WINDOW - 1 tokens
(the guarantee threshold) are certain to share a fingerprint; runs shorter than K (noise: ``V = V - V``)
never count. Hashes are CRC-32 based, so the same text gives the same fingerprints in every process.
"""

from __future__ import annotations

import zlib
from collections.abc import Sequence

K = 6          # tokens in a k-gram: a short statement (``V = V . V ;``) alone matches nothing
WINDOW = 4     # hashes per window; a match of K + WINDOW - 1 = 9 tokens (about a line) is always seen


def kgram_hashes(words: Sequence[str], k: int = K) -> list[int]:
    """The hash of each k-gram of ``words`` (empty when there are fewer than k words)."""
    ids = [zlib.crc32(w.encode("utf-8", "surrogatepass")) for w in words]
    return [hash(tuple(ids[i:i + k])) & 0xFFFFFFFFFFFF for i in range(len(ids) - k + 1)]


def winnow(hashes: Sequence[int], window: int = WINDOW) -> list[tuple[int, int]]:
    """The fingerprints as (hash, position of its k-gram), in order of position.

    A position is recorded once; a document shorter than one window keeps its smallest hash."""
    if not hashes:
        return []
    if len(hashes) <= window:
        pos = min(range(len(hashes)), key=lambda i: (hashes[i], -i))
        return [(hashes[pos], pos)]
    picked: list[tuple[int, int]] = []
    last = -1
    for start in range(len(hashes) - window + 1):
        # the rightmost minimum of the window (robust winnowing: fewer picks on runs of equal hashes)
        pos = start
        for i in range(start + 1, start + window):
            if hashes[i] <= hashes[pos]:
                pos = i
        if pos != last:
            picked.append((hashes[pos], pos))
            last = pos
    return picked
