#!/usr/bin/env bash
# Whole-process timing of `rotor-rub simulate` for the benchmark issue's targets, every method at
# tol = 1e-10 (hyperfine if installed, `apt-get install hyperfine`; else a plain timing loop):
#   contact-sparse (paper preset, offset (0, 0), η = 1.5), 100 000 forcing periods:
#       analytic vs dop853 (target: ≥ 10× faster), hybrid for reference;
#   contact-heavy (paper preset, η = 2.5), 10 000 forcing periods:
#       hybrid vs dop853 (target: ≥ 1.5×, stretch 2×), analytic for reference.
# Usage: scripts/cli_targets.sh [PATH/TO/rotor-rub]  (default: builds the release binary)
set -euo pipefail
cd "$(dirname "$0")/.."
bin="${1:-}"
if [[ -z "$bin" ]]; then
    cargo build --release -q -p rotor-rub-cli
    bin="${CARGO_TARGET_DIR:-target}/release/rotor-rub"
fi
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
sparse=(--set speed_ratio=1.5 --set offset_x=0 --set offset_y=0 --periods 100000 --tol 1e-10)
heavy=(--set speed_ratio=2.5 --periods 10000 --tol 1e-10)

time_cmd() { # name, args... -> prints "name mean_seconds"
    local name="$1"
    shift
    if command -v hyperfine > /dev/null; then
        hyperfine -N --warmup 1 --min-runs 5 --export-json "$out/$name.json" "$*" > "$out/$name.txt"
        python3 -c "import json,sys; r=json.load(open(sys.argv[1]))['results'][0]; print(sys.argv[2], r['median'], r['stddev'])" "$out/$name.json" "$name"
    else
        python3 - "$name" "$@" <<'PY'
import statistics, subprocess, sys, time
name, cmd = sys.argv[1], sys.argv[2:]
subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
runs = []
for _ in range(5):
    t = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    runs.append(time.perf_counter() - t)
print(name, statistics.median(runs), statistics.stdev(runs))
PY
    fi
}

{
    time_cmd sparse-analytic "$bin" simulate --method analytic "${sparse[@]}"
    time_cmd sparse-hybrid "$bin" simulate --method hybrid "${sparse[@]}"
    time_cmd sparse-dop853 "$bin" simulate --method dop853 "${sparse[@]}"
    time_cmd heavy-hybrid "$bin" simulate --method hybrid "${heavy[@]}"
    time_cmd heavy-analytic "$bin" simulate --method analytic "${heavy[@]}"
    time_cmd heavy-dop853 "$bin" simulate --method dop853 "${heavy[@]}"
} | tee "$out/times.txt"

python3 - "$out/times.txt" <<'PY'
import sys
t = {}
for line in open(sys.argv[1]):
    name, median, sd = line.split()
    t[name] = float(median)
print()
print("| case (tol = 1e-10) | method | median wall time | vs dop853 |")
print("|---|---|---:|---:|")
for case, periods in (("sparse", "100 000"), ("heavy", "10 000")):
    base = t[f"{case}-dop853"]
    for m in ("analytic", "hybrid", "dop853"):
        key = f"{case}-{m}"
        if key in t:
            print(f"| contact-{case}, {periods} periods | {m} | {t[key] * 1e3:.1f} ms | {base / t[key]:.1f}× |")
PY
