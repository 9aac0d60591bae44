"""WRONG VERSION (tests/sandbox/test_probe_batch.py): a worker that answers `probe_many` wrongly, in the
way its config's `lie` names (what a compromised worker could send on its channel):

- honest: one answer per probe, ids id, id + 1, ... (the value of each is its position in the batch);
- too_many: one answer more than asked for, written together with the last one;
- too_few: the last answer left out (the worker then waits for the next request);
- out_of_order: the first two answers swapped;
- forged_id: the second answer with an id nobody asked for.

Any other request gets an empty success (`load` an empty load report). Started by the grader's runner
like the real worker: its last argument is the JSON config with the pipe descriptors (or, on the portable
channel, "channel": "stdio": requests on stdin, answers on stdout).
"""

import json
import os
import sys


def main() -> None:
    config = json.loads(sys.argv[-1])
    lie = config["lie"]
    if config.get("channel") == "stdio":  # the portable channel (grader.sandbox.channel): standard pipes
        fd_in, fd_out = 0, 1
    else:
        fd_in, fd_out = int(config["fd_in"]), int(config["fd_out"])

    def line(message: dict) -> bytes:
        return json.dumps(message).encode() + b"\n"

    os.write(fd_out, line({"id": 0, "ok": True, "value": {"pid": os.getpid()}}))
    pending = b""
    while True:
        while b"\n" not in pending:
            data = os.read(fd_in, 65536)
            if not data:
                return
            pending += data
        raw, pending = pending.split(b"\n", 1)
        request = json.loads(raw)
        rid = request["id"]
        if request["op"] != "probe_many":
            value = {"modules": {}, "errors": []} if request["op"] == "load" else None
            os.write(fd_out, line({"id": rid, "ok": True, "value": value}))
            continue
        ids = list(range(rid, rid + len(request["probes"])))
        if lie == "too_many":
            ids.append(ids[-1] + 1)
        elif lie == "too_few":
            ids.pop()
        elif lie == "out_of_order":
            ids[0], ids[1] = ids[1], ids[0]
        elif lie == "forged_id":
            ids[1] = rid + 1000
        os.write(fd_out, b"".join(line({"id": k, "ok": True, "value": k - rid}) for k in ids))


if __name__ == "__main__":
    main()
