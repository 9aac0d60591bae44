"""Compare every pair of students by the winnowed fingerprints of their code blocks.

A pair's score is the share of the smaller side's fingerprints that the other side has too (1.0: all of
the shorter submission's code is in the longer one). Fingerprints of the handout's own blocks are
nobody's, and so are those found in more than ``max_common`` submissions (MOSS's ``-m``: the formula
every correct solution writes, the wheel speeds of ``uni_to_diff``, is no sign of copying in a class of
400).
By default that is 10 (MOSS's) or a tenth of the class, whichever is more: a solution passed around 30
of 400 students still shows.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from itertools import combinations

from grader.similarity.fingerprints import WINDOW, K, kgram_hashes, winnow
from grader.similarity.submitted import ComparedBlock, StudentCode
from grader.similarity.tokens import Token, block_tokens

MAX_COMMON = 10        # MOSS's default: a passage in more submissions than this is common knowledge
COMMON_SHARE = 0.1     # ... or in more than this share of the class, whichever is more
MAX_PLACES = 16        # places kept per fingerprint: a line repeated 10,000 times is marked 16 times, and a
                       # pair's work stays bounded (places of one side times places of the other)


@dataclass
class Prints:
    """One student's fingerprints: hash -> the places [(block index, first token)] it was taken from."""

    code: StudentCode
    tokens: list[list[Token]]
    places: dict[int, list[tuple[int, int]]] = field(default_factory=dict)


@dataclass
class Pair:
    """Two students and what they share. ``spans`` are, per side, {block index: [(start, end) chars]}."""

    a: StudentCode
    b: StudentCode
    score: float
    shared: int
    sizes: tuple[int, int]
    blocks: list[dict]
    spans: tuple[dict[int, list[tuple[int, int]]], dict[int, list[tuple[int, int]]]]


def fingerprints(code: StudentCode, ignored: set[int] | frozenset[int] = frozenset()) -> Prints:
    """The winnowed fingerprints of a student's blocks, without those in ``ignored``. Each block is
    fingerprinted on its own, so that reordering whole blocks or files changes nothing."""
    prints = Prints(code, [])
    for index, block in enumerate(code.blocks):
        tokens = block_tokens(block.compared)
        prints.tokens.append(tokens)
        for value, pos in winnow(kgram_hashes([t.text for t in tokens])):
            places = prints.places.setdefault(value, []) if value not in ignored else None
            if places is not None and len(places) < MAX_PLACES:
                places.append((index, pos))
    return prints


def all_kgrams(blocks: Sequence[ComparedBlock]) -> set[int]:
    """Every k-gram hash of ``blocks`` (the handout's: all of them, not only the winnowed ones)."""
    found: set[int] = set()
    for block in blocks:
        found.update(kgram_hashes([t.text for t in block_tokens(block.compared)]))
    return found


def common_limit(students: int) -> int:
    """The default ``max_common`` of a class of ``students``."""
    return max(MAX_COMMON, math.ceil(COMMON_SHARE * students))


def compare(codes: Sequence[StudentCode], handout: Sequence[ComparedBlock],
            max_common: int | None = None) -> list[Pair]:
    """Every pair sharing a fingerprint, best score first (ties by the number shared, then by ids).
    ``max_common`` None: common_limit of the class."""
    max_common = common_limit(len(codes)) if max_common is None else max_common
    ignored = all_kgrams(handout)
    prints = [fingerprints(code, ignored) for code in codes]
    holders: dict[int, list[int]] = {}
    for i, p in enumerate(prints):
        for value in p.places:
            holders.setdefault(value, []).append(i)
    common = {value for value, who in holders.items() if len(who) > max_common}
    for p in prints:
        for value in common & p.places.keys():
            del p.places[value]
    holders = {value: who for value, who in holders.items() if value not in common}
    shared: dict[tuple[int, int], list[int]] = {}
    for value, who in holders.items():
        for i, j in combinations(who, 2):
            shared.setdefault((i, j), []).append(value)
    pairs = [_pair(prints[i], prints[j], values) for (i, j), values in shared.items()]
    pairs.sort(key=lambda p: (-p.score, -p.shared, p.a.id, p.b.id))
    return pairs


def _pair(a: Prints, b: Prints, values: list[int]) -> Pair:
    smaller = min(len(a.places), len(b.places))
    per_block: dict[tuple[int, int], int] = {}
    for value in values:
        for ia, _ in a.places[value]:
            for ib, _ in b.places[value]:
                per_block[(ia, ib)] = per_block.get((ia, ib), 0) + 1
    blocks = [{"a": a.code.blocks[ia].label, "b": b.code.blocks[ib].label, "shared": n}
              for (ia, ib), n in sorted(per_block.items(), key=lambda kv: (-kv[1], kv[0]))]
    return Pair(a.code, b.code, round(len(values) / smaller, 4) if smaller else 0.0, len(values),
                (len(a.places), len(b.places)), blocks, (_spans(a, values), _spans(b, values)))


def _spans(p: Prints, values: list[int]) -> dict[int, list[tuple[int, int]]]:
    """Per block, the merged character spans of the k-grams behind ``values``."""
    raw: dict[int, list[tuple[int, int]]] = {}
    for value in values:
        for index, pos in p.places[value]:
            tokens = p.tokens[index]
            raw.setdefault(index, []).append((tokens[pos].start, tokens[pos + K - 1].end))
    merged: dict[int, list[tuple[int, int]]] = {}
    for index, spans in raw.items():
        out: list[tuple[int, int]] = []
        for start, end in sorted(spans):
            if out and start <= out[-1][1]:
                out[-1] = (out[-1][0], max(out[-1][1], end))
            else:
                out.append((start, end))
        merged[index] = out
    return merged


__all__ = ["K", "WINDOW", "MAX_COMMON", "Pair", "common_limit", "compare", "fingerprints"]
