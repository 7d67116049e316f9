"""Each result type as tables and back (what :mod:`rotor_rub._io` converts and saves): the
columns of every table, in order, and the scalars that go with them. The first table is the
result's main one."""

from __future__ import annotations

from typing import Any, Callable, Dict, Mapping, Tuple

import numpy as np

from ._io import Tables, codes, join_state, split_state
from .results import (
    EVENT_KINDS,
    REGIMES,
    Events,
    Jump,
    Problem,
    Run,
    Runup,
    RunupEvents,
    Samples,
    Section,
    Spectrum,
    Steps,
    Sweep,
)

Scalars = Dict[str, Any]


def _samples(s: Samples) -> Dict[str, np.ndarray]:
    return {"time": s.time, **split_state(s.state), "regime": s.regime}


def _events(e: Events) -> Dict[str, np.ndarray]:
    return {"time": e.time, "kind": e.kind, **split_state(e.state)}


def _samples_from(t: Mapping[str, np.ndarray]) -> Samples:
    return Samples(t["time"], join_state(t), codes(t["regime"], REGIMES))


def _events_from(t: Mapping[str, np.ndarray]) -> Events:
    return Events(t["time"], codes(t["kind"], EVENT_KINDS), join_state(t))


def _run(r: Run) -> Tuple[Tables, Scalars]:
    scalars: Scalars = {k: float(getattr(r, k)) for k in (
        "start_time", "end_time", "time_free", "time_contact", "time_rolling",
        "contact_fraction", "forcing_period", "elapsed")}
    scalars["end_state"] = [float(v) for v in r.end_state]
    return {"sample": _samples(r.samples), "event": _events(r.events)}, scalars


def _run_from(t: Tables, m: Mapping[str, Any]) -> Run:
    s = m["scalars"]
    return Run(events=_events_from(t["event"]), samples=_samples_from(t["sample"]),
               end_state=np.array(s["end_state"], dtype=np.float64),
               problem=Problem.from_dict(m["problem"]),
               **{k: v for k, v in s.items() if k != "end_state"})


def _steps(r: Steps) -> Tuple[Tables, Scalars]:
    return {"sample": _samples(r.samples), "event": _events(r.events)}, {}


def _steps_from(t: Tables, m: Mapping[str, Any]) -> Steps:
    return Steps(samples=_samples_from(t["sample"]), events=_events_from(t["event"]),
                 problem=Problem.from_dict(m["problem"]))


def _section(r: Section) -> Tuple[Tables, Scalars]:
    return ({"point": {"period": r.period, **split_state(r.state)}},
            {"response": r.response, "lyapunov": r.lyapunov, "distinct": r.distinct})


def _section_from(t: Tables, m: Mapping[str, Any]) -> Section:
    s = m["scalars"]
    return Section(period=t["point"]["period"], state=join_state(t["point"]),
                   response=s["response"], lyapunov=s["lyapunov"], distinct=s["distinct"],
                   problem=Problem.from_dict(m["problem"]))


def _spectrum(r: Spectrum) -> Tuple[Tables, Scalars]:
    cols: Dict[str, np.ndarray] = {"order": r.order}
    for name in ("x", "y", "whirl"):
        values = getattr(r, name)
        if values is not None:
            cols[name] = values
    return {"bin": cols}, {}


def _spectrum_from(t: Tables, m: Mapping[str, Any]) -> Spectrum:
    b = t["bin"]
    return Spectrum(order=b["order"], x=b.get("x"), y=b.get("y"), whirl=b.get("whirl"),
                    problem=Problem.from_dict(m["problem"]))


def _sweep(r: Sweep) -> Tuple[Tables, Scalars]:
    rows: Dict[str, np.ndarray] = {name: r.values[:, j] for j, name in enumerate(r.params)}
    rows.update({"period": r.period, **split_state(r.state), "point": r.point})
    points: Dict[str, np.ndarray] = {name: r.points[:, j] for j, name in enumerate(r.params)}
    points["response"] = r.response
    if r.lyapunov is not None:
        points["lyapunov"] = r.lyapunov
    return ({"row": rows, "point": points},
            {"params": list(r.params), "skipped": list(r.skipped)})


def _sweep_from(t: Tables, m: Mapping[str, Any]) -> Sweep:
    names = tuple(m["scalars"]["params"])
    rows, points = t["row"], t["point"]
    width = len(names)
    return Sweep(
        params=names,
        values=np.stack([rows[n] for n in names], axis=1).reshape(-1, width),
        period=rows["period"], state=join_state(rows),
        skipped=tuple(m["scalars"]["skipped"]), point=rows["point"],
        points=np.stack([points[n] for n in names], axis=1).reshape(-1, width),
        response=points["response"], lyapunov=points.get("lyapunov"),
        problem=Problem.from_dict(m["problem"]))


_RUNUP_ROWS = ("direction", "period", "start", "end", "speed", "speed_change", "max_radius",
               "min_radius", "contact_fraction", "whirl", "whirl_direction", "enters", "exits")


def _runup(r: Runup) -> Tuple[Tables, Scalars]:
    rows = {c: getattr(r, c) for c in _RUNUP_ROWS}
    e = r.events
    events = {"time": e.time, "speed": e.speed, "period": e.period, "direction": e.direction,
              "kind": e.kind, **split_state(e.state)}
    jumps = {
        "speed": np.array([j.speed for j in r.jumps], dtype=np.float64),
        "direction": np.array([j.direction for j in r.jumps], dtype=np.str_),
        "before": np.array([j.before for j in r.jumps], dtype=np.float64),
        "after": np.array([j.after for j in r.jumps], dtype=np.float64),
        "period": np.array([j.period for j in r.jumps], dtype=np.int64),
    }
    return ({"row": rows, "event": events, "jump": jumps},
            {"program": r.program, "elapsed": r.elapsed})


def _runup_from(t: Tables, m: Mapping[str, Any]) -> Runup:
    e, j = t["event"], t["jump"]
    events = RunupEvents(e["time"], codes(e["kind"], EVENT_KINDS), join_state(e),
                         speed=e["speed"], period=e["period"], direction=e["direction"])
    jumps = tuple(Jump(float(s), str(d), float(b), float(a), int(p)) for s, d, b, a, p in
                  zip(j["speed"], j["direction"], j["before"], j["after"], j["period"]))
    return Runup(**{c: t["row"][c] for c in _RUNUP_ROWS}, events=events, jumps=jumps,
                 program=m["scalars"]["program"], elapsed=m["scalars"]["elapsed"],
                 problem=Problem.from_dict(m["problem"]))


CONVERTERS: Dict[type, Tuple[Callable[[Any], Tuple[Tables, Scalars]],
                             Callable[[Tables, Mapping[str, Any]], Any]]] = {
    Run: (_run, _run_from),
    Steps: (_steps, _steps_from),
    Section: (_section, _section_from),
    Spectrum: (_spectrum, _spectrum_from),
    Sweep: (_sweep, _sweep_from),
    Runup: (_runup, _runup_from),
}
