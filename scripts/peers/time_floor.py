"""Where the long-run error floor of our methods comes from: absolute time in f64.

Why: over 1000 forcing periods of the contact-heavy case (heyoka_contact.py) the switch-time
error of hybrid and dop853 stops improving near 1e-10 from tol 1e-12 on, while heyoka (which
keeps its time in double-length arithmetic) floors near 2e-11. This script runs the same
trajectory two ways and measures both against the 30-digit reference
(data/contact_heavy_1000.csv, made by `mp_reference.py --case heavy1000`):

* one run over τ ∈ [0, 2513.27] (the usual way);
* ten chained runs of 100 forcing periods each, every one restarted at τ = 0 from the previous
  run's end state. 100 periods at η = 2.5 are τ = 80π, so the forcing phase at each restart is
  exactly 0 mod 2π and the chain is the same trajectory; only the absolute time seen by the
  method stays below 251 instead of growing to 2513. The reference times are shifted by 80πk in
  multiple precision before comparing.

If the chained error is much smaller, the floor is rounding of absolute time and of the phase
ητ + φ0, not of the integrator.

Usage: scripts/peers/run time_floor.py
"""

from __future__ import annotations

import os
import sys
from typing import Dict, List, Tuple

from mpmath import mp, mpf

import rotor_rub as rr
from mp_reference import read_switch_times

HERE = os.path.dirname(os.path.abspath(__file__))
ETA = 2.5
CHUNKS = 10


def reference() -> List[Tuple[str, mpf]]:
    return read_switch_times(os.path.join(HERE, "data", "contact_heavy_1000.csv"), mpf)


def main() -> int:
    mp.dps = 40
    ref = reference()
    chunk = 80 * mp.pi  # 100 forcing periods 2π/η at η = 2.5
    print(f"contact-heavy case (paper, η = {ETA}), {CHUNKS} × 100 periods; max|Δt| against the "
          f"30-digit reference ({len(ref)} switches), whole run and its last 400 switches")
    print(f"{'method':<8} {'tol':>6}  {'one run':>9} {'last 400':>9}  {'chained':>9} {'last 400':>9}")
    for method in ("hybrid", "dop853"):
        for tol in (1e-10, 1e-12, 1e-14):
            one = rr.simulate(preset="paper", speed_ratio=ETA, t_end=float(chunk * CHUNKS),
                              method=method, tol=tol, samples=2)
            kinds = [str(k) for k in one.events.kind]
            if kinds != [k for k, _ in ref]:
                print(f"{method} {tol:g}: one run's switches differ from the reference")
                continue
            e_one: List[mpf] = [abs(mpf(float(t)) - rt)
                                for t, (_, rt) in zip(one.events.time, ref)]
            errs: List[mpf] = []
            state: List[float] = []
            idx = 0
            ok = True
            for k in range(CHUNKS):
                start: Dict[str, float] = dict(zip(("x0", "y0", "vx0", "vy0"), state))
                run = rr.simulate(preset="paper", speed_ratio=ETA, t_end=float(chunk),
                                  method=method, tol=tol, samples=2,
                                  **start)  # type: ignore[arg-type]
                for t, kind in zip(run.events.time, run.events.kind):
                    if idx >= len(ref) or ref[idx][0] != str(kind):
                        ok = False
                        break
                    errs.append(abs(mpf(float(t)) - (ref[idx][1] - chunk * k)))
                    idx += 1
                state = [float(v) for v in run.end_state]
            if not ok or idx != len(ref):
                print(f"{method} {tol:g}: the chained switches differ from the reference")
                continue
            print(f"{method:<8} {tol:6.0e}  {float(max(e_one)):9.1e} {float(max(e_one[-400:])):9.1e}"
                  f"  {float(max(errs)):9.1e} {float(max(errs[-400:])):9.1e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
