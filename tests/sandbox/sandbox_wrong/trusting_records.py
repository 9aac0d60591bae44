"""Wrong version of grader.inside.step_record.StepLayout.decode_answer: it reads the record's values, its
strings sliced by the lengths the record itself declares, before it checks the frame's size against the
layout. A truncated or padded record then decodes into a command (shorter strings, values shifted)
instead of a protocol violation. tests/sandbox/test_step_records.py must catch it."""

from __future__ import annotations

from typing import Any

from grader.inside.step_record import StepLayout


class TrustingLayout(StepLayout):
    def decode_answer(self, payload: bytes) -> dict:
        if len(payload) < self.answer.size:  # only enough to unpack: the rest is trusted
            payload = bytes(payload) + bytes(self.answer.size - len(payload))
        raw = self.answer.unpack_from(payload)
        fixed, state_len = self.answer.size, raw[5]
        state = bytes(payload[fixed:fixed + state_len]).decode("utf-8", "replace")
        at = self._floats + len(self._scalars)
        debug: dict[str, Any] = dict(zip(self._scalars, raw[self._floats:at], strict=True))
        pairs = iter(raw[at:at + 2 * len(self._vectors)])
        debug.update(zip(self._vectors, map(list, zip(pairs, pairs, strict=True)), strict=True))
        at += 2 * len(self._vectors)
        for name, n in self._points:
            debug[name] = [list(raw[at:at + n]), list(raw[at + n:at + 2 * n])]
            at += 2 * n
        debug.update(zip(self._counts, raw[self._counts_at:self._flags_at], strict=True))
        debug.update(zip(self._flags, map(bool, raw[self._flags_at]), strict=True))
        end = fixed + state_len
        for name, length in zip(self._labels, raw[self._labels_at:], strict=True):
            debug[name] = bytes(payload[end:end + length]).decode("utf-8", "replace")
            end += length
        for name, present in zip(self.names, raw[6], strict=True):
            if not present:
                debug[name] = None
        return {"vel_r": raw[0], "vel_l": raw[1], "estimate": [raw[2], raw[3], raw[4]], "state": state,
                "debug": debug}
