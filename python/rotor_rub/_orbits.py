"""Periodic orbits: :func:`orbit` finds one by shooting (Newton's method on k forcing periods of
the stroboscopic map, with the monodromy matrix from the segments), with its Floquet
multipliers and stability; :func:`continuation` follows branches of them over a parameter and
locates their folds, period doublings (switching to the period-2k branch), Neimark–Sacker and
grazing points. The numbers of ``rotor-rub orbit`` and ``rotor-rub continue``
(``docs/MODEL.md`` §18)."""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _core, _progress
from ._io import Result, Tables, join_state, split_state
from .results import Count, FloatArray, IntArray, PathLike, Problem, Real, StrArray

ComplexArray = npt.NDArray[np.complex128]
BoolArray = npt.NDArray[np.bool_]
#: Where Newton starts: ``"simulate"`` (after ``transient`` forcing periods), ``"free"`` (the
#: steady response without contact, in closed form) or a state (x, y, x', y').
Guess = Union[str, Sequence[Real], FloatArray, None]

#: Bifurcation kinds, as in the branch CSV's ``bifurcation`` column.
BIFURCATION_KINDS: Tuple[str, ...] = ("fold", "period-doubling", "neimark-sacker", "grazing")


def _path(config: Optional[PathLike]) -> Optional[str]:
    return None if config is None else os.fspath(config)


def _complex(re: Any, im: Any) -> ComplexArray:
    return np.asarray(re, dtype=np.float64) + 1j * np.asarray(im, dtype=np.float64)


@dataclass
class Orbit(Result):
    """A periodic orbit (:func:`orbit`): ``state`` on the section τ = 0 mod the forcing period
    (x, y, x', y'), ``period`` k in forcing periods (a fixed point of k periods) and
    ``minimal_period`` its own (the response class period-j of a Poincaré section on it),
    ``multipliers`` (complex, largest modulus first), ``stable`` (every multiplier inside the
    unit circle), ``monodromy`` (4 × 4), ``sections`` (the states after 1 … k periods),
    ``residuals`` (Newton's |P^k(s) − s| per iterate), ``start`` (where Newton started), the
    largest and smallest radius |q|, the contact fraction and the contacts per orbit."""

    state: FloatArray
    period: int
    minimal_period: int
    multipliers: ComplexArray
    stable: bool
    monodromy: FloatArray
    sections: FloatArray
    residuals: FloatArray
    start: FloatArray
    max_radius: float
    min_radius: float
    contact_fraction: float
    contacts: int
    problem: Problem

    @property
    def method(self) -> str:
        return self.problem.method_text


@dataclass(frozen=True)
class Bifurcation:
    """A bifurcation located on a branch: ``kind`` (fold, period-doubling, neimark-sacker,
    grazing), the parameter ``value``, the orbit's ``state`` and ``period``, its ``multipliers``,
    the ``branch`` and the ``index`` of its row in the :class:`Continuation`."""

    kind: str
    value: float
    state: FloatArray
    period: int
    multipliers: ComplexArray
    branch: int
    index: int


@dataclass(frozen=True)
class Branch:
    """A branch of a :class:`Continuation`: its ``id``, its orbits' ``period``, the row of the
    period doubling it was switched to from (``parent``, None for a first branch) and why it
    ``end``-ed."""

    id: int
    period: int
    parent: Optional[int]
    end: str


@dataclass
class Continuation(Result):
    """Branches of periodic orbits over ``param`` (:func:`continuation`), one entry per point in
    branch order, each located bifurcation a point of its own: ``value`` (the parameter),
    ``state`` (n × 4, on the section), ``period``, ``stable``, ``multipliers`` (n × 4, complex),
    ``branch``, ``kind`` ("" or the bifurcation), ``max_radius``, ``min_radius``,
    ``contact_fraction``, ``contacts``; ``bifurcations`` the located points, ``branches`` each
    branch's period, parent and end; ``evaluations`` the map evaluations, ``elapsed`` seconds.
    The rows of ``rotor-rub continue``'s CSV."""

    param: str
    value: FloatArray
    state: FloatArray
    period: IntArray
    stable: BoolArray
    multipliers: ComplexArray
    branch: IntArray
    kind: StrArray
    max_radius: FloatArray
    min_radius: FloatArray
    contact_fraction: FloatArray
    contacts: IntArray
    branches: Tuple[Branch, ...]
    evaluations: int
    elapsed: float
    problem: Problem

    @property
    def bifurcations(self) -> Tuple[Bifurcation, ...]:
        """The located bifurcations, in branch order."""
        rows = np.flatnonzero(self.kind != "")
        return tuple(
            Bifurcation(kind=str(self.kind[i]), value=float(self.value[i]),
                        state=self.state[i], period=int(self.period[i]),
                        multipliers=self.multipliers[i], branch=int(self.branch[i]),
                        index=int(i))
            for i in rows)

    @property
    def method(self) -> str:
        return self.problem.method_text

    def __len__(self) -> int:
        return int(self.value.shape[0])


def orbit(
    *,
    preset: Optional[str] = None,
    config: Optional[PathLike] = None,
    period: Count = 1,
    guess: Guess = None,
    transient: Count = 200,
    newton_tol: Real = 1e-10,
    method: Optional[str] = None,
    tol: Optional[Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[Real] = None,
    max_work: Optional[Real] = None,
    progress: Any = None,
    **params: Real,
) -> Orbit:
    """One periodic orbit by shooting: a fixed point of ``period`` forcing periods of the
    stroboscopic map, found by Newton's method from ``guess`` (``"simulate"``, the default: the
    state after ``transient`` forcing periods from the initial state; ``"free"``: the steady
    response without contact; or a state x, y, x', y'), to ``newton_tol`` (relative to
    1 + |s|, in [1e-14, 1e-3]). The monodromy comes from the segments: closed-form free flight,
    the variational equations in contact, saltation at the switches. Each map runs ``method``
    (default ``hybrid``) at ``tol`` (default 1e-12 here). The numbers of ``rotor-rub orbit``.

    Returns
    -------
    Orbit
        ``.state``, ``.period``, ``.multipliers`` (complex), ``.stable`` and more.

    Raises
    ------
    ValueError
        Invalid input, naming the keyword, the value and its valid range.
    PropagationError
        No orbit found from the guess (Newton did not converge), or a failed propagation.
    KeyboardInterrupt
        Ctrl-C, within about 50 ms.
    """
    start = None if guess is None or isinstance(guess, str) else np.asarray(guess)
    r = _progress.run(lambda report: _core.orbit(
        preset=preset, config=_path(config), period=period,
        guess=guess if start is None else start, transient=transient, newton_tol=newton_tol,
        method=method, tol=tol, contact_scheme=contact_scheme, step=step, max_work=max_work,
        progress=report, params=params), progress, "orbit", "periods")
    options = {"preset": preset, "config": _path(config), "period": int(period),
               "guess": guess if start is None else [float(v) for v in start],
               "transient": int(transient), "newton_tol": float(newton_tol)}
    return Orbit(
        state=r["state"],
        period=int(r["period"]),
        minimal_period=int(r["minimal_period"]),
        multipliers=_complex(r["multipliers_re"], r["multipliers_im"]),
        stable=bool(r["stable"]),
        monodromy=np.asarray(r["monodromy"]).reshape(4, 4),
        sections=r["sections"],
        residuals=r["residuals"],
        start=r["start"],
        max_radius=float(r["max_radius"]),
        min_radius=float(r["min_radius"]),
        contact_fraction=float(r["contact_fraction"]),
        contacts=int(r["contacts"]),
        problem=Problem._of(r["problem"], "orbit", options),
    )


def continuation(
    param: str,
    start: Real,
    stop: Real,
    *,
    preset: Optional[str] = None,
    config: Optional[PathLike] = None,
    period: Count = 1,
    guess: Guess = None,
    transient: Count = 200,
    max_period: Optional[Count] = None,
    max_points: Count = 3000,
    newton_tol: Real = 1e-10,
    method: Optional[str] = None,
    tol: Optional[Real] = None,
    contact_scheme: Optional[str] = None,
    step: Optional[Real] = None,
    max_work: Optional[Real] = None,
    progress: Any = None,
    **params: Real,
) -> Continuation:
    """Branches of periodic orbits over ``param`` (any model parameter) from ``start`` to
    ``stop``: the period-``period`` orbit at ``start`` (from ``guess`` as in :func:`orbit`),
    followed by pseudo-arclength continuation through folds, with the bifurcations located to
    1e-8 in the parameter: fold (a multiplier through +1), period doubling (through −1; the
    period-2k branch born there is followed while 2k ≤ ``max_period``, default 2·``period``),
    Neimark–Sacker (a complex pair through the unit circle) and grazing (a contact appears or
    vanishes along the orbit). A branch ends where the parameter leaves the range, after
    ``max_points`` points, or where it closes. ``progress`` in percent of the range reached.
    The rows of ``rotor-rub continue``'s CSV.

    Returns
    -------
    Continuation
        Arrays ``.value``, ``.state``, ``.period``, ``.stable``, ``.multipliers`` and
        ``.bifurcations`` (each with ``.kind`` and ``.value``).

    Raises
    ------
    ValueError
        Invalid input (not a model parameter, a value out of its range, equal ends, …).
    PropagationError
        No orbit at the start, or a failed propagation.
    KeyboardInterrupt
        Ctrl-C, within about 50 ms.
    """
    initial = None if guess is None or isinstance(guess, str) else np.asarray(guess)
    r = _progress.run(lambda report: _core.continuation(
        param, start, stop, preset=preset, config=_path(config), period=period,
        guess=guess if initial is None else initial, transient=transient,
        max_period=max_period, max_points=max_points, newton_tol=newton_tol, method=method,
        tol=tol, contact_scheme=contact_scheme, step=step, max_work=max_work,
        progress=report, params=params), progress, "continuation", "% of the range",
        whole=False)
    n = len(r["value"])
    options = {"preset": preset, "config": _path(config), "param": str(param),
               "start": float(start), "stop": float(stop), "period": int(period),
               "guess": guess if initial is None else [float(v) for v in initial],
               "transient": int(transient),
               "max_period": None if max_period is None else int(max_period),
               "max_points": int(max_points), "newton_tol": float(newton_tol)}
    return Continuation(
        param=r["param"],
        value=r["value"],
        state=r["state"],
        period=r["period"].astype(np.int64),
        stable=np.asarray(r["stable"], dtype=np.bool_),
        multipliers=_complex(r["multipliers_re"], r["multipliers_im"]).reshape(n, 4),
        branch=r["branch"].astype(np.int64),
        kind=np.asarray(r["kind"], dtype=np.str_),
        max_radius=r["max_radius"],
        min_radius=r["min_radius"],
        contact_fraction=r["contact_fraction"],
        contacts=r["contacts"].astype(np.int64),
        branches=tuple(Branch(id=int(b["id"]), period=int(b["period"]),
                              parent=None if b["parent"] is None else int(b["parent"]),
                              end=str(b["end"])) for b in r["branches"]),
        evaluations=int(r["evaluations"]),
        elapsed=float(r["elapsed"]),
        problem=Problem._of(r["problem"], "continuation", options),
    )


# Tables and files (rotor_rub._io): complex numbers as real and imaginary columns.

def _orbit_tables(o: Orbit) -> Tuple[Tables, Dict[str, Any]]:
    m = o.multipliers
    tables: Tables = {
        "multiplier": {"re": m.real.copy(), "im": m.imag.copy(), "modulus": np.abs(m)},
        "section": {"period": np.arange(1, o.period + 1, dtype=np.int64),
                    **split_state(o.sections)},
        "residual": {"iterate": np.arange(len(o.residuals), dtype=np.int64),
                     "residual": o.residuals},
    }
    scalars = {"state": [float(v) for v in o.state], "period": o.period,
               "minimal_period": o.minimal_period, "stable": o.stable,
               "monodromy": [float(v) for v in o.monodromy.ravel()],
               "start": [float(v) for v in o.start], "max_radius": o.max_radius,
               "min_radius": o.min_radius, "contact_fraction": o.contact_fraction,
               "contacts": o.contacts}
    return tables, scalars


def _orbit_from(t: Tables, m: Mapping[str, Any]) -> Orbit:
    s = m["scalars"]
    mult = t["multiplier"]
    return Orbit(
        state=np.array(s["state"], dtype=np.float64), period=int(s["period"]),
        minimal_period=int(s["minimal_period"]),
        multipliers=_complex(mult["re"], mult["im"]), stable=bool(s["stable"]),
        monodromy=np.array(s["monodromy"], dtype=np.float64).reshape(4, 4),
        sections=join_state(t["section"]), residuals=t["residual"]["residual"],
        start=np.array(s["start"], dtype=np.float64), max_radius=float(s["max_radius"]),
        min_radius=float(s["min_radius"]), contact_fraction=float(s["contact_fraction"]),
        contacts=int(s["contacts"]), problem=Problem.from_dict(m["problem"]))


_POINT_COLUMNS = ("value", "period", "stable", "branch", "kind", "max_radius", "min_radius",
                  "contact_fraction", "contacts")


def _continuation_tables(c: Continuation) -> Tuple[Tables, Dict[str, Any]]:
    point: Dict[str, np.ndarray] = {name: getattr(c, name) for name in _POINT_COLUMNS}
    # Booleans as 0/1: every file format keeps integers.
    point["stable"] = c.stable.astype(np.int8)
    point.update(split_state(c.state))
    for j in range(4):
        point[f"multiplier_{j + 1}_re"] = c.multipliers[:, j].real.copy()
        point[f"multiplier_{j + 1}_im"] = c.multipliers[:, j].imag.copy()
    scalars = {"param": c.param, "evaluations": c.evaluations, "elapsed": c.elapsed,
               "branches": [{"id": b.id, "period": b.period, "parent": b.parent, "end": b.end}
                            for b in c.branches]}
    return {"point": point}, scalars


def _continuation_from(t: Tables, m: Mapping[str, Any]) -> Continuation:
    p, s = t["point"], m["scalars"]
    multipliers = np.stack([_complex(p[f"multiplier_{j + 1}_re"], p[f"multiplier_{j + 1}_im"])
                            for j in range(4)], axis=1)
    return Continuation(
        param=s["param"], state=join_state(p), multipliers=multipliers,
        branches=tuple(Branch(**b) for b in s["branches"]),
        evaluations=int(s["evaluations"]), elapsed=float(s["elapsed"]),
        problem=Problem.from_dict(m["problem"]),
        **{name: np.asarray(p[name]).astype(bool) if name == "stable" else p[name]
           for name in _POINT_COLUMNS})


def _register() -> None:
    from ._tables import CONVERTERS

    CONVERTERS[Orbit] = (_orbit_tables, _orbit_from)
    CONVERTERS[Continuation] = (_continuation_tables, _continuation_from)


_register()
