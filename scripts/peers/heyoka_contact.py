"""Peer comparison for issue 16: heyoka (Taylor integration with event detection) against
rotor-rub's own methods on a contact-heavy case, in time and in switch-time accuracy.

Why: the `taylor` method (exact free flight + a generated Taylor integrator in contact, switches
as polynomial roots) has to be judged against the established Taylor integrator a user would
reach for. heyoka is driven from Python the way a user would do it: two `taylor_adaptive`
integrators, one on the free field and one on the contact field, each with a terminal event on
z² − 1 = 0 (free: upward crossings, contact: downward), the state handed from one to the other
at every switch.

Case "contact-heavy": the `paper` preset (docs/MODEL.md §9) at speed ratio η = 2.5 (a
quasi-periodic rub, about 4 switches per forcing period), 1000 forcing periods 2π/η, tol 1e-10.

What is measured, all in one process:

* heyoka's JIT compilation time (constructing both integrators; excluded from the run times);
* wall time of each run: best and median of `--repeats` repeats; for heyoka also the part of it
  that is Python and call overhead of the handoffs (the same calls with nothing to integrate);
* every switch time. Accuracy is max |Δt| over the switches matched in order against a
  reference: the 30-digit switch times of mp_reference.py (data/contact_heavy_<periods>.csv)
  when that file exists, else heyoka at tol 1e-15 (independent of our code; with the mp file
  the error against heyoka at 1e-15 is printed beside, column "vs hy15"). The count and the
  kinds must match, otherwise the mismatch is reported (and the error over the common prefix
  before it).
* our methods through the Python binding (`rotor_rub.simulate(..., samples=2)`): "hybrid",
  "dop853" and "taylor" when the installed package accepts it (a ValueError naming the method
  means it does not: skipped with a note). When "taylor" exists its tol-1e-15 run (1e-14 when
  1e-15 is out of its range) is also compared with heyoka's tol-1e-15 run (a cross-check).

Equal-accuracy rule: the target error E is the max switch-time error of heyoka's run at the
case's tolerance (1e-10) — the accuracy a user gets from the peer at the tolerance asked for
(`--target taylor` uses our taylor method's instead, when it exists). For every method the
tolerance ladder 1e-8, 1e-9, …, 1e-14 is walked from loose to tight and the first (loosest)
tolerance whose error is ≤ E is taken; the ratios of those rows compare methods at equal
switch-time accuracy. A method that reaches E nowhere on the ladder is reported as such. Because
over 1000 periods rounding puts a floor under every double-precision run (heyoka ~2e-11, our
methods ~1e-10, growing with τ: time_floor.py), the same selection is also printed at the fixed levels 1e-8,
1e-9 and 1e-10.

Usage: scripts/peers/run heyoka_contact.py [--quick] (see scripts/peers/README.md).
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import time
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional, Sequence, Tuple

import heyoka as hy
import numpy as np

import rotor_rub as rr
from mp_reference import read_switch_times

LADDER: Tuple[float, ...] = (1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14)
OUR_METHODS: Tuple[str, ...] = ("hybrid", "dop853", "taylor")
# Switch-time error levels at which the methods are also compared (besides the target).
FIXED_LEVELS: Tuple[float, ...] = (1e-8, 1e-9, 1e-10)

Switches = List[Tuple[str, float]]


@dataclass
class Case:
    """The model parameters of one case (names as `rotor_rub.parameters()`)."""

    name: str
    preset: str
    overrides: Dict[str, float]
    values: Dict[str, float]
    t_end: float

    @staticmethod
    def make(name: str, preset: str, periods: float, **overrides: float) -> "Case":
        values = dict(rr.presets()[preset])
        values.setdefault("start_time", 0.0)  # not a preset value: the table's default
        values.update(overrides)
        t_end = periods * 2.0 * math.pi / values["speed_ratio"]
        return Case(name, preset, overrides, values, t_end)


@dataclass
class Run:
    """One measured configuration: times of the repeats and the switches of the last repeat."""

    method: str
    tol: float
    times: List[float]
    switches: Switches
    jit: Optional[float] = None
    note: str = ""
    error: Optional[float] = None
    error_note: str = ""
    extra: Dict[str, Optional[float]] = field(default_factory=dict)

    @property
    def best(self) -> float:
        return min(self.times)

    @property
    def median(self) -> float:
        return statistics.median(self.times)


# ---------------------------------------------------------------------------------------------
# heyoka: two integrators, handing the state off at every switch


class HeyokaPair:
    """The free-field and the contact-field integrators of one case at one tolerance.

    The field is the model of docs/MODEL.md §1 (codegen/src/model/mod.rs):
    q'' = F (cos θ, sin θ) + u − 2ν q' − q − [contact] K_s g(q), g = (1 − 1/z)(q − ε̂),
    z = |q − ε̂|, θ = η τ + φ0, F = η_m ρ̂ η². Frictionless only (μ = 0).
    """

    def __init__(self, case: Case, tol: float, handoff: str = "nudge") -> None:
        """`handoff`: what is done to the state handed over at a switch. heyoka misses a
        crossing later in a step whose event function is exactly 0 at the step's start (seen at
        tol 1e-11: a 0.146-long free flight skipped, 6 switches lost in 100 periods), and the
        handed-over state sits on z = 1 to rounding. "nudge" (default, free) moves the position
        radially by 1e-15 (relative) onto the new regime's side, as rotor-rub itself does with
        3e-14 (docs/MODEL.md §12); "step" takes a first step of 1e-9 before propagating (about
        30 % slower); "none" hands the state over as it is (shows the miss)."""
        if handoff not in ("nudge", "step", "none"):
            raise ValueError(f"handoff {handoff!r}: expected nudge, step or none")
        self.handoff = handoff
        p = case.values
        if p["friction_coefficient"] != 0.0:
            raise ValueError("the heyoka peer states the frictionless model only")
        x, y, vx, vy = hy.make_vars("x", "y", "vx", "vy")
        eta, nu = p["speed_ratio"], p["damping_ratio"]
        f = p["mass_ratio"] * p["eccentricity_ratio"] * eta * eta
        theta = eta * hy.time + p["phase"]
        u = x - p["offset_x"]
        v = y - p["offset_y"]
        free_x = f * hy.cos(theta) + p["force_x"] - 2.0 * nu * vx - x
        free_y = f * hy.sin(theta) + p["force_y"] - 2.0 * nu * vy - y
        scale = 1.0 - 1.0 / hy.sqrt(u * u + v * v)
        gx, gy = scale * u, scale * v
        contact_x = free_x - (p["k_xx"] * gx + p["k_xy"] * gy)
        contact_y = free_y - (p["k_yx"] * gx + p["k_yy"] * gy)
        h = u * u + v * v - 1.0
        start = [p["x0"], p["y0"], p["vx0"], p["vy0"]]
        hy.llvm_state.clear_memcache()  # the JIT time below is a fresh compilation
        t0 = time.perf_counter()
        self.free = hy.taylor_adaptive(
            [(x, vx), (y, vy), (vx, free_x), (vy, free_y)],
            start,
            time=p["start_time"],
            tol=tol,
            t_events=[hy.t_event(h, direction=hy.event_direction.positive)],
        )
        self.contact = hy.taylor_adaptive(
            [(x, vx), (y, vy), (vx, contact_x), (vy, contact_y)],
            start,
            time=p["start_time"],
            tol=tol,
            t_events=[hy.t_event(h, direction=hy.event_direction.negative)],
        )
        self.jit = time.perf_counter() - t0
        self.ex, self.ey = p["offset_x"], p["offset_y"]
        self.case = case
        self.start = np.array(start, dtype=float)
        zu, zv = start[0] - p["offset_x"], start[1] - p["offset_y"]
        if abs(zu * zu + zv * zv - 1.0) < 1e-12:
            raise ValueError("start on z = 1: not handled by this peer")
        self.start_in_contact = zu * zu + zv * zv > 1.0

    def run(self) -> Tuple[Switches, np.ndarray]:
        """Propagate from the case's start to its end: the switches (kind, time) and the
        state at every switch (n, 4)."""
        t = self.case.values["start_time"]
        state = self.start.copy()
        ta = self.contact if self.start_in_contact else self.free
        switches: Switches = []
        states: List[np.ndarray] = []
        t_end = self.case.t_end
        while True:
            ta.time = t
            ta.state[:] = state
            ta.reset_cooldowns()
            if switches and self.handoff == "step":
                # A short first step (1e-9) moves off the zero; the crossing just left is
                # filtered out by the event's direction.
                outcome = ta.step(max_delta_t=min(1e-9, t_end - t))[0]
                if outcome != hy.taylor_outcome.success and outcome != hy.taylor_outcome.time_limit:
                    raise RuntimeError(f"guard step stopped with {outcome!r} at t = {ta.time}")
            outcome = ta.propagate_until(t_end)[0]
            if outcome == hy.taylor_outcome.time_limit:
                return switches, np.array(states).reshape(-1, 4)
            if int(outcome) != -1:  # a terminal event without callback reports -(index)-1
                raise RuntimeError(f"heyoka stopped with {outcome!r} at t = {ta.time}")
            t = ta.time
            state = ta.state.copy()
            switches.append(("enter" if ta is self.free else "exit", t))
            states.append(state.copy())
            if self.handoff == "nudge":
                # move the position radially by 1e-15 (relative) onto the new regime's side
                f = 1.0 + 1e-15 if ta is self.free else 1.0 - 1e-15
                state[0] = self.ex + (state[0] - self.ex) * f
                state[1] = self.ey + (state[1] - self.ey) * f
            ta = self.contact if ta is self.free else self.free


    def overhead(self, count: int) -> float:
        """Wall time of `count` handoffs that integrate nothing (set time and state, reset
        cooldowns, a zero-length propagate_until, read the state back): the Python and call
        overhead a run with count − 1 switches pays on top of heyoka's compiled integration.
        Best of 3."""
        ta = self.free
        s = self.start.copy()
        best = math.inf
        for _ in range(3):
            t0 = time.perf_counter()
            for _ in range(count):
                ta.time = 1.0
                ta.state[:] = s
                ta.reset_cooldowns()
                ta.propagate_until(1.0)
                s = ta.state.copy()
            best = min(best, time.perf_counter() - t0)
        return best


def time_heyoka(case: Case, tol: float, repeats: int) -> Run:
    pair = HeyokaPair(case, tol)
    times = []
    switches: Switches = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        switches, _ = pair.run()
        times.append(time.perf_counter() - t0)
    run = Run("heyoka", tol, times, switches, jit=pair.jit)
    overhead = pair.overhead(len(switches) + 1)
    run.extra["overhead"] = overhead
    run.note = f"Python handoffs ≈ {1e3 * overhead:.2f} ms of it"
    return run


# ---------------------------------------------------------------------------------------------
# our methods, through the Python binding


def time_ours(case: Case, method: str, tol: float, repeats: int) -> Optional[Run]:
    """Best-of-`repeats` wall time of `rotor_rub.simulate`; None when the installed package
    does not know the method (or refuses this tolerance), with the message printed."""
    times = []
    switches: Switches = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        try:
            r = rr.simulate(
                preset=case.preset,
                t_end=case.t_end,
                method=method,
                tol=tol,
                samples=2,
                **case.overrides,  # type: ignore[arg-type]
            )
        except ValueError as e:
            print(f"  note: {method} at tol {tol:g} skipped: {e}", file=sys.stderr)
            return None
        times.append(time.perf_counter() - t0)
        switches = [(str(k), float(t)) for k, t in zip(r.events.kind, r.events.time)]
    return Run(method, tol, times, switches)


def method_available(method: str) -> bool:
    try:
        rr.simulate(preset="paper", t_end=1.0, method=method, samples=2)
    except ValueError as e:
        print(f"note: method {method!r} not in the installed rotor_rub ({e}); skipped",
              file=sys.stderr)
        return False
    return True


# ---------------------------------------------------------------------------------------------
# accuracy


def compare(run: Switches, reference: Switches) -> Tuple[Optional[float], str]:
    """Max |Δt| over the switches matched in order, or None and a note when count or kinds
    differ (the note gives the error over the common prefix before the first difference)."""
    n = min(len(run), len(reference))
    first_bad = next((i for i in range(n) if run[i][0] != reference[i][0]), n)
    prefix = max((abs(run[i][1] - reference[i][1]) for i in range(first_bad)), default=0.0)
    if len(run) == len(reference) and first_bad == n:
        return prefix, ""
    where = (
        f"kind differs at switch {first_bad} (t≈{reference[first_bad][1]:.6f})"
        if first_bad < n
        else f"count {len(run)} vs {len(reference)}"
    )
    return None, f"mismatch: {where}; max|Δt| before it {prefix:.1e}"


# ---------------------------------------------------------------------------------------------
# the table

HERE = os.path.dirname(os.path.abspath(__file__))


def load_mp_reference(periods: float) -> Optional[Switches]:
    """The 30-digit switch times of the case from mp_reference.py (`--case heavy100` /
    `heavy1000`), when that file exists."""
    path = os.path.join(HERE, "data", f"contact_heavy_{periods:g}.csv")
    if not os.path.exists(path):
        return None
    return read_switch_times(path, float)


def print_table(title: str, runs: Sequence[Run], hybrid_best: Optional[float],
                second: bool) -> None:
    print(f"\n{title}")
    head = f"{'method':<8} {'tol':>7} {'best ms':>9} {'median ms':>10} {'/hybrid':>8} " \
           f"{'switches':>8} {'max|Δt|':>9}" + (f" {'vs hy15':>9}" if second else "") + "  note"
    print(head)
    print("-" * len(head))
    for r in runs:
        ratio = f"{r.best / hybrid_best:8.3f}" if hybrid_best else f"{'—':>8}"
        err = f"{r.error:9.1e}" if r.error is not None else f"{'—':>9}"
        if second:
            e2 = r.extra.get("vs_hy15")
            err += f" {e2:9.1e}" if e2 is not None else f" {'—':>9}"
        note = "; ".join(x for x in (r.error_note, r.note) if x)
        print(f"{r.method:<8} {r.tol:7.0e} {1e3 * r.best:9.2f} {1e3 * r.median:10.2f} {ratio} "
              f"{len(r.switches):8d} {err}  {note}")


def main(argv: Optional[Sequence[str]] = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true",
                    help="100 periods, 3 repeats (default: 1000 periods, 7 repeats)")
    ap.add_argument("--periods", type=float, help="override the number of forcing periods")
    ap.add_argument("--repeats", type=int, help="override the number of repeats")
    ap.add_argument("--taylor-name", default="taylor", metavar="METHOD",
                    help="the method treated as our taylor method (default taylor; another name, "
                    "e.g. analytic, dry-runs the taylor rows before the method exists)")
    ap.add_argument("--target", choices=("heyoka", "taylor"), default="heyoka",
                    help="whose tol-1e-10 error sets the equal-accuracy level")
    ap.add_argument("--reference", choices=("auto", "heyoka", "mp"), default="auto",
                    help="what max|Δt| is measured against: heyoka at tol 1e-15, or the "
                    "30-digit mp_reference.py file for this many periods (auto: mp when the "
                    "file exists; the other column then gives the error against heyoka 1e-15)")
    ap.add_argument("--switches", metavar="CSV",
                    help="write every switch of every run (method,tol,index,kind,time) here")
    args = ap.parse_args(argv)
    periods = args.periods or (100.0 if args.quick else 1000.0)
    repeats = args.repeats or (3 if args.quick else 7)
    tol = 1e-10
    case = Case.make("contact-heavy", "paper", periods, speed_ratio=2.5)
    print(f"case {case.name}: preset {case.preset}, {case.overrides}, {periods:g} forcing "
          f"periods (τ_end = {case.t_end:.6f}), tol {tol:g}, {repeats} repeats; "
          f"heyoka {hy.__version__}, rotor_rub {rr.__version__}")

    ours = [args.taylor_name if m == "taylor" else m for m in OUR_METHODS]
    methods = [m for m in ours if method_available(m)]

    # references
    hy15 = time_heyoka(case, 1e-15, 1)
    print(f"heyoka tol 1e-15: {len(hy15.switches)} switches (JIT {1e3 * (hy15.jit or 0):.1f} ms)")
    mp_ref = None if args.reference == "heyoka" else load_mp_reference(periods)
    if args.reference == "mp" and mp_ref is None:
        print(f"no mp reference for {periods:g} periods: run mp_reference.py --case "
              f"heavy{periods:g} first", file=sys.stderr)
        return 2
    if mp_ref is not None:
        reference, ref_name = mp_ref, "the 30-digit mp reference"
        e, note = compare(hy15.switches, mp_ref)
        print(f"30-digit mp reference: {len(mp_ref)} switches; heyoka at tol 1e-15 against it: "
              f"max|Δt| = {'—' if e is None else f'{e:.1e}'} {note}")
    else:
        reference, ref_name = hy15.switches, "heyoka at tol 1e-15"
    second = mp_ref is not None

    def measure(r: Run) -> None:
        r.error, r.error_note = compare(r.switches, reference)
        if second:
            r.extra["vs_hy15"] = compare(r.switches, hy15.switches)[0]  # type: ignore

    # the handoff pitfall, shown once
    bare = HeyokaPair(case, 1e-11, handoff="none").run()[0]
    print(f"heyoka tol 1e-11 with the state handed over as it is (no nudge): {len(bare)} "
          f"switches, {compare(bare, reference)[1] or 'no miss'}")

    # the case at tol 1e-10
    main_runs: List[Run] = []
    hy_run = time_heyoka(case, tol, repeats)
    hy_run.note = f"JIT {1e3 * (hy_run.jit or 0):.1f} ms excluded; " + hy_run.note
    main_runs.append(hy_run)
    for m in methods:
        r = time_ours(case, m, tol, repeats)
        if r is not None:
            main_runs.append(r)
    for r in main_runs:
        measure(r)
    hybrid_best = next((r.best for r in main_runs if r.method == "hybrid"), None)
    print_table(f"tol {tol:g} (max|Δt| against {ref_name})", main_runs, hybrid_best, second)

    cross: List[Run] = []
    if args.taylor_name in methods:
        # its tightest tolerance: 1e-15 when accepted, else 1e-14
        t15 = time_ours(case, args.taylor_name, 1e-15, 1) or time_ours(
            case, args.taylor_name, 1e-14, 1)
        if t15 is not None:
            measure(t15)
            e, note = compare(t15.switches, hy15.switches)
            t15.note = f"cross-check: ours at {t15.tol:g} vs heyoka at 1e-15: " + (
                note or f"{e:.1e}")
            cross.append(t15)
            print_table("cross-check of the references", cross, hybrid_best, second)

    # the ladder
    ladder: Dict[str, List[Run]] = {"heyoka": []}
    for m in methods:
        ladder[m] = []
    for t in LADDER:
        ladder["heyoka"].append(hy_run if t == tol else time_heyoka(case, t, repeats))
        for m in methods:
            r = next((x for x in main_runs if x.method == m and x.tol == t), None)
            r = r or time_ours(case, m, t, repeats)
            if r is not None:
                ladder[m].append(r)
    for runs in ladder.values():
        for r in runs:
            measure(r)
    ladder_rows = [r for runs in ladder.values() for r in runs]
    hybrid_at_tol = next((r.best for r in ladder["hybrid"] if r.tol == tol), hybrid_best)
    print_table("tolerance ladder", ladder_rows, hybrid_at_tol, second)

    wanted = args.taylor_name if args.target == "taylor" else "heyoka"
    target_runs = ladder.get(wanted) or ladder["heyoka"]
    target_name = wanted if ladder.get(wanted) else "heyoka"
    target = next((r.error for r in target_runs if r.tol == tol), None)
    if target is None:
        print(f"\n{target_name} at tol {tol:g} has no switch error (mismatch): the fixed "
              "levels only")
    levels = sorted({*FIXED_LEVELS, *([target] if target is not None else [])}, reverse=True)
    for level in levels:
        rows: List[Run] = []
        missing: List[str] = []
        for name, runs in ladder.items():
            hit = next((r for r in runs if r.error is not None and r.error <= level), None)
            if hit is None:
                missing.append(name)
            else:
                rows.append(hit)
        equal_hybrid = next((r.best for r in rows if r.method == "hybrid"), None)
        what = f" = {target_name} at tol {tol:g}" if level == target else ""
        print_table(f"equal accuracy: loosest ladder tol with max|Δt| ≤ {level:.1e}{what}", rows,
                    equal_hybrid, second)
        if missing:
            print(f"  not reached on the ladder (1e-8 … 1e-14): {', '.join(missing)}")

    if args.switches:
        with open(args.switches, "w") as out:
            out.write("method,tol,index,kind,time\n")
            for r in [hy15] + main_runs + cross + ladder_rows:
                for i, (k, t) in enumerate(r.switches):
                    out.write(f"{r.method},{r.tol:g},{i},{k},{t!r}\n")
        print(f"\nswitches written to {args.switches}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
