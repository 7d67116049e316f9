#!/usr/bin/env python3
"""Compare two output dumps of `tests/output_identity.rs` (DUMP=path) number by number.

    scripts/compare_dumps.py before.txt after.txt

Prints, per run that differs, the largest relative difference of its switch times and of its
states (events and samples), whether its event kinds agree, and a summary over every run: what a
change that moves bits on purpose reports in its commit. Only the standard library is used.
"""

import struct
import sys


def parse(path):
    runs = {}
    name = None
    for line in open(path):
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "run":
            name = " ".join(parts[1:])
            runs[name] = []
            continue
        if parts[0] in ("event", "sample"):
            kind = parts[1] if parts[0] == "event" else "sample"
            words = parts[2:] if parts[0] == "event" else parts[1:]
            values = [struct.unpack(">d", bytes.fromhex(w))[0] for w in words]
            runs[name].append((parts[0], kind, values))
        else:
            runs[name].append(("error", line.strip(), []))
    return runs


def rel(a, b):
    scale = max(abs(a), abs(b), 1e-300)
    return abs(a - b) / max(scale, 1.0)


def main():
    before, after = parse(sys.argv[1]), parse(sys.argv[2])
    worst_time = worst_state = 0.0
    differing = kinds_differ = 0
    for name, rows in before.items():
        other = after.get(name)
        if other is None:
            print(f"{name}: missing after")
            continue
        if rows == other:
            continue
        differing += 1
        kinds_a = [(r[0], r[1]) for r in rows]
        kinds_b = [(r[0], r[1]) for r in other]
        if kinds_a != kinds_b:
            kinds_differ += 1
            events_a = sum(1 for r in rows if r[0] == "event")
            events_b = sum(1 for r in other if r[0] == "event")
            print(f"{name}: event sequence differs ({events_a} -> {events_b} events)")
            continue
        dt = ds = 0.0
        for (what, _, va), (_, _, vb) in zip(rows, other):
            if what == "event":
                dt = max(dt, rel(va[0], vb[0]))
            ds = max(ds, max((rel(a, b) for a, b in zip(va[1:], vb[1:])), default=0.0))
        worst_time, worst_state = max(worst_time, dt), max(worst_state, ds)
        print(f"{name}: switch times {dt:.2e}, states {ds:.2e}")
    print(
        f"{differing} of {len(before)} runs differ; {kinds_differ} in their event sequence; "
        f"largest relative difference: switch times {worst_time:.2e}, states {worst_state:.2e}"
    )


if __name__ == "__main__":
    main()
