"""Attack: appended to a week-3 differential_drive.py (tests/sandbox/test_step_records.py). `forge(how)`
replaces the worker's step records so that every later answer is the honest record changed in one way, or
sends a step record where a JSON answer is due. Each must end as a protocol violation in the grader."""
import os
import struct
import sys

_HEADER = struct.Struct("<BII")


def _mutate(how, frame, layout):
    kind, rid, size = _HEADER.unpack_from(frame)
    payload = bytearray(frame[_HEADER.size:])
    fixed = layout.answer.size
    presence = 5 * 8 + 2  # after the five doubles and the state's length
    if how == "truncated":           # one byte short, the header's length told the truth about it
        payload = payload[:-1]
    elif how == "longer":            # one byte more than its fields
        payload += b"x"
    elif how == "header_lies":       # the header says one byte more than is sent, then the next frame
        return _HEADER.pack(kind, rid, size + 1) + bytes(payload)
    elif how == "oversize":          # a length beyond any answer
        return _HEADER.pack(kind, rid, 1 << 30) + bytes(payload)
    elif how == "bad_utf8":          # the state's bytes are not UTF-8
        state_len = struct.unpack_from("<H", payload, 40)[0]
        payload[fixed:fixed + state_len] = b"\xff" * state_len
    elif how == "state_too_long":    # a state longer than its cap, with the bytes to match
        payload[40:42] = struct.pack("<H", 60000)
        payload += b"a" * (60000 - struct.unpack_from("<H", frame, _HEADER.size + 40)[0])
    elif how == "presence_2":        # a presence byte that is neither 0 nor 1
        payload[presence] = 2
    elif how == "wrong_kind":        # a readings record where an answer is due
        kind = 1
    elif how == "wrong_id":          # the answer to another question
        rid += 7
    elif how == "twice":             # the answer, and the same answer again, unasked
        return frame + frame
    elif how == "nan_speed":         # a well-formed record whose speed is NaN: an invalid command, as in JSON
        payload[0:8] = struct.pack("<d", float("nan"))
    return _HEADER.pack(kind, rid, len(payload)) + bytes(payload)


def forge(how="truncated", **args):
    step_record = sys.modules["grader.inside.step_record"]
    honest = step_record.StepLayout.writer

    def writer(self, brain):
        write = honest(self, brain)

        def forged(rid):
            frame = write(rid)
            return _mutate(how, frame, self) if type(frame) is bytes else frame

        return forged

    step_record.StepLayout.writer = writer


def unasked(**args):
    """Every later JSON answer replaced by a step record (the grader asked for JSON)."""
    def send(fd, message):
        data = _HEADER.pack(2, message["id"], 3) + b"abc"
        os.write(fd, data)

    sys.modules["grader.inside.worker_loop"]._send = send
