#!/usr/bin/env python3
"""Collect the medians of the last `cargo bench` run from criterion's output into Markdown tables.

Usage: scripts/bench_table.py [TARGET_DIR]   (default: $CARGO_TARGET_DIR or ./target)

For every benchmark group one table: benchmark, median, and the ratio to the group's `dop853`
entry (and to `peer-dop853` where present): "× faster" > 1 means faster than DOP853. The
accuracy table written by `benches/propagation.rs` (rotor-rub-accuracy.csv) is printed too.
"""
import csv
import json
import os
import sys
from collections import defaultdict


def fmt_time(ns):
    if ns >= 1e9:
        return f"{ns / 1e9:.3g} s"
    if ns >= 1e6:
        return f"{ns / 1e6:.3g} ms"
    if ns >= 1e3:
        return f"{ns / 1e3:.3g} µs"
    return f"{ns:.3g} ns"


def main():
    target = sys.argv[1] if len(sys.argv) > 1 else os.environ.get("CARGO_TARGET_DIR", "target")
    root = os.path.join(target, "criterion")
    groups = defaultdict(list)
    for dirpath, _dirs, files in os.walk(root):
        if os.path.basename(dirpath) != "new" or "benchmark.json" not in files:
            continue
        with open(os.path.join(dirpath, "benchmark.json")) as f:
            bench = json.load(f)
        with open(os.path.join(dirpath, "estimates.json")) as f:
            est = json.load(f)
        name = bench["function_id"] or ""
        if bench.get("value_str"):
            name = f"{name} ({bench['value_str']})" if name else bench["value_str"]
        median = est["median"]["point_estimate"]
        throughput = bench.get("throughput") or {}
        groups[bench["group_id"]].append((name, median, throughput))
    for group in sorted(groups):
        rows = sorted(groups[group], key=lambda r: r[1])
        base = next((m for n, m, _ in rows if n.startswith("dop853 ")), None)
        peer = [m for n, m, _ in rows if n.startswith("peer-dop853 ")]
        print(f"\n#### {group}\n")
        head = "| benchmark | median |"
        rule = "|---|---:|"
        if base:
            head += " vs our DOP853 |"
            rule += "---:|"
        if peer:
            head += " vs peer DOP853 |"
            rule += "---:|"
        if any(t for _, _, t in rows):
            head += " throughput |"
            rule += "---:|"
        print(head)
        print(rule)
        for name, median, throughput in rows:
            line = f"| {name} | {fmt_time(median)} |"
            if base:
                line += f" {base / median:.2f}× |"
            if peer:
                line += " " + " / ".join(f"{p / median:.2f}×" for p in peer) + " |"
            if throughput:
                n = throughput.get("Elements") or throughput.get("Bytes")
                line += f" {n / (median * 1e-9):,.0f} /s |" if n else " |"
            print(line)
    acc = os.path.join(root, "rotor-rub-accuracy.csv")
    if os.path.exists(acc):
        print("\n#### accuracy against DOP853 at tol = 1e-13 (100 periods)\n")
        print("| case | method | knob | switch-time error | state error | meets 1e-8 / 1e-6 |")
        print("|---|---|---|---:|---:|---|")
        with open(acc) as f:
            for r in csv.DictReader(f):
                ok = "yes" if r["meets"] == "true" else "no"
                if r["unmatched"] != "0":
                    ok += f" ({r['unmatched']} unmatched)"
                print(f"| {r['case']} | {r['method']} | {r['knob']} | "
                      f"{float(r['switch_time_error']):.1e} | {float(r['state_error']):.1e} | {ok} |")


if __name__ == "__main__":
    main()
