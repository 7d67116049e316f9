"""Rotors from matrices with a rub station (issue 29): :class:`Rub`, :class:`Model`.

A model is the user's linear rotor in SI units, M q'' + (C + Ω G) q' + K q = unbalance + force +
(contact force at the rub station), with the contact law of the paper at the station: the
rotor point (``dof_x``, ``dof_y``) against a fixed stator or a stator point that is itself a DOF
pair. Inside, lengths are scaled by the clearance δ (q/δ, m·e/δ); time (s), the speed (rad/s)
and the matrices stay as given; results come back in SI. The checks, the statement and the
messages are the model files' (docs/MODEL_FILES.md): a model built here and the same model read
from a TOML or ``.npz`` file are the same model.

Sources: :meth:`Model.from_matrices` (numpy arrays), :meth:`Model.from_file` (a model file),
:meth:`Model.from_ross` (a ``ross.Rotor``, or the ``.npz`` that ``scripts/ross/export_rotor.py``
writes from one), optionally reduced to its lowest modes (:func:`craig_bampton`).
"""

from __future__ import annotations

import math
import numbers
import os
from dataclasses import dataclass
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union, cast

import numpy as np
import numpy.typing as npt

from . import _core

FloatArray = npt.NDArray[np.float64]
Stiffness = Union[float, Sequence[Sequence[float]], FloatArray]

__all__ = ["Rub", "Model", "craig_bampton"]


def _real(name: str, value: Any) -> float:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Real, np.number)):
        raise ValueError(f"{name} = {value!r} must be a real number")
    x = float(value)
    if not math.isfinite(x):
        raise ValueError(f"{name} = {x} is not a finite number")
    return x


def _dof(name: str, value: Any, names: Optional[Sequence[str]] = None) -> int:
    if names is not None and isinstance(value, str):
        if value not in names:
            raise ValueError(f"{name} = {value!r} is not a degree of freedom of the model: "
                             f"the DOFs are {', '.join(names)}")
        return list(names).index(value)
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Integral, np.integer)):
        raise ValueError(f"{name} = {value!r} must be a DOF index (an integer ≥ 0)")
    i = int(value)
    if i < 0:
        raise ValueError(f"{name} = {i} is out of range: a DOF index must be ≥ 0")
    return i


def _stiffness(value: Stiffness) -> Tuple[Tuple[float, float], Tuple[float, float]]:
    a = np.asarray(value, dtype=object)
    if a.ndim == 0:
        k = _real("rub.contact_stiffness", value)
        return ((k, 0.0), (0.0, k))
    if a.shape != (2, 2):
        raise ValueError(f"rub.contact_stiffness has shape {a.shape}; it must be a number "
                         "(N/m) or a 2 × 2 matrix [[kxx, kxy], [kyx, kyy]]")
    rows = [[_real(f"rub.contact_stiffness[{i}][{j}]", a[i, j]) for j in range(2)]
            for i in range(2)]
    return ((rows[0][0], rows[0][1]), (rows[1][0], rows[1][1]))


@dataclass(frozen=True)
class Rub:
    """The rub station: where the rotor rubs and how (SI units).

    ``dof_x``, ``dof_y``: the rotor point's DOFs (indices, or names when the model names its
    DOFs); ``clearance`` δ, m (radial gap at rest); ``contact_stiffness`` K_c, N/m, a number k
    (k·I) or a 2 × 2 matrix; ``friction_coefficient`` μ; ``radius`` R, m, the rotor's radius at
    the station (needed with friction: the surface speed ΩR sets the slip); ``offset``: the
    stator centre from the rotor point's rest position, m; ``stator``: None for a fixed stator,
    or the DOF pair (x, y) of a stator point that moves (a ring with mass)."""

    dof_x: Union[int, str]
    dof_y: Union[int, str]
    clearance: float
    contact_stiffness: Stiffness
    friction_coefficient: float = 0.0
    radius: Optional[float] = None
    offset: Tuple[float, float] = (0.0, 0.0)
    stator: Optional[Tuple[Union[int, str], Union[int, str]]] = None

    def __post_init__(self) -> None:
        for name in ("dof_x", "dof_y"):
            v = getattr(self, name)
            if not isinstance(v, str):
                object.__setattr__(self, name, _dof(f"rub.{name}", v))
        object.__setattr__(self, "clearance", _real("rub.clearance", self.clearance))
        k = _stiffness(self.contact_stiffness)
        if np.ndim(np.asarray(self.contact_stiffness, dtype=object)) == 0:
            object.__setattr__(self, "contact_stiffness", k[0][0])
        else:
            object.__setattr__(self, "contact_stiffness", k)
        object.__setattr__(self, "friction_coefficient",
                           _real("rub.friction_coefficient", self.friction_coefficient))
        if self.radius is not None:
            object.__setattr__(self, "radius", _real("rub.radius", self.radius))
        try:
            off = tuple(self.offset) if not isinstance(self.offset, str) else ()
        except TypeError:
            off = ()
        if len(off) != 2:
            raise ValueError(f"rub.offset = {self.offset!r} must be a pair (x, y) in m")
        object.__setattr__(self, "offset", (_real("rub.offset[0]", off[0]),
                                            _real("rub.offset[1]", off[1])))
        if self.stator is not None:
            try:
                s = tuple(self.stator) if not isinstance(self.stator, str) else ()
            except TypeError:
                s = ()
            if len(s) != 2:
                raise ValueError(f"rub.stator = {self.stator!r} must be None (a fixed stator) "
                                 "or a DOF pair (x, y)")
            object.__setattr__(self, "stator", tuple(
                v if isinstance(v, str) else _dof(f"rub.stator[{i}]", v)
                for i, v in enumerate(s)))

    def _resolved(self, names: Sequence[str]) -> "Rub":
        """This station with DOF names replaced by indices into ``names``."""
        stator = None if self.stator is None else (
            _dof("rub.stator[0]", self.stator[0], names),
            _dof("rub.stator[1]", self.stator[1], names))
        return Rub(_dof("rub.dof_x", self.dof_x, names), _dof("rub.dof_y", self.dof_y, names),
                   self.clearance, self.contact_stiffness, self.friction_coefficient,
                   self.radius, self.offset, stator)

    def _core(self) -> Dict[str, Any]:
        return {"dof_x": self.dof_x, "dof_y": self.dof_y, "stator": self.stator,
                "clearance": self.clearance,
                "contact_stiffness": [list(r) for r in _stiffness(self.contact_stiffness)],
                "friction_coefficient": self.friction_coefficient, "radius": self.radius,
                "offset": self.offset}


def _matrix(name: str, value: Any) -> FloatArray:
    try:
        a = np.array(value, dtype=np.float64, copy=True)
    except (TypeError, ValueError) as e:
        raise ValueError(f"{name} must be a 2-D array of real numbers: {e}") from None
    if a.ndim != 2:
        raise ValueError(f"{name} has {a.ndim} dimensions (shape {a.shape}); it must be a "
                         "2-D n × n array")
    a = np.ascontiguousarray(a)
    a.setflags(write=False)
    return a


Unbalance = Tuple[Union[int, str], Union[int, str], float, float]


class Model:
    """A linear rotor from matrices with a rub station, SI units (see the module's doc).

    Build one with :meth:`from_matrices`, :meth:`from_file` or :meth:`from_ross`; simulate it
    with ``rotor_rub.simulate(model=model, …)``. Attributes: ``M``, ``C``, ``G``, ``K`` (read-only
    numpy arrays), ``speed`` Ω (rad/s), ``phase`` (rad), ``unbalance`` (tuples ``(dof_x, dof_y,
    m_e, phase)``, kg·m and rad), ``force`` (N per DOF or None), ``station`` (the :class:`Rub`,
    DOFs as indices), ``dofs`` (names), ``n``, ``initial`` (positions, velocities or None),
    ``speed_dependent`` (``(speed, C, K)`` points), ``name``, ``reduction`` (what a reduction
    kept, or None). Models pickle (Dask) and compare equal when every value is equal.
    """

    def __init__(self, *, M: Any, K: Any, C: Any = None, G: Any = None,
                 unbalance: Sequence[Unbalance] = (), rub: Rub, speed: float,
                 dofs: Optional[Sequence[str]] = None, phase: float = 0.0,
                 force: Optional[Sequence[float]] = None,
                 initial: Optional[Sequence[float]] = None,
                 speed_dependent: Sequence[Tuple[float, Any, Any]] = (), name: str = "",
                 reduction: Optional[Mapping[str, Any]] = None) -> None:
        self.M = _matrix("M", M)
        n = self.M.shape[0]
        self.K = _matrix("K", K)
        self.C = _matrix("C", np.zeros((n, n)) if C is None else C)
        self.G = _matrix("G", np.zeros((n, n)) if G is None else G)
        names = [f"q{i}" for i in range(n)] if dofs is None else [str(d) for d in dofs]
        if dofs is not None and (isinstance(dofs, str) or len(names) != n):
            raise ValueError(f"dofs has {len(names)} names; the model has n = {n} degrees of "
                             "freedom (M is n × n)")
        self.dofs: Tuple[str, ...] = tuple(names)
        self.speed = _real("speed", speed)
        self.phase = _real("phase", phase)
        if not isinstance(rub, Rub):
            raise ValueError(f"rub = {rub!r} must be a rotor_rub.Rub(dof_x, dof_y, clearance, "
                             "contact_stiffness, …)")
        self.station: Rub = rub._resolved(self.dofs)
        ub = []
        for i, given in enumerate(unbalance):
            u: Tuple[Any, ...] = tuple(given)
            if len(u) != 4:
                raise ValueError(f"unbalance[{i}] = {u!r} must be (dof_x, dof_y, m_e, phase): "
                                 "DOFs, kg·m, rad")
            ub.append((_dof(f"unbalance[{i}].dof_x", u[0], self.dofs),
                       _dof(f"unbalance[{i}].dof_y", u[1], self.dofs),
                       _real(f"unbalance[{i}].m_e", u[2]), _real(f"unbalance[{i}].phase", u[3])))
        self.unbalance: Tuple[Tuple[int, int, float, float], ...] = tuple(ub)
        self.force: Optional[Tuple[float, ...]] = None if force is None else tuple(
            _real(f"force[{i}]", f) for i, f in enumerate(force))
        if initial is None:
            self.initial: Optional[Tuple[float, ...]] = None
        else:
            init = tuple(_real(f"initial[{i}]", x) for i, x in enumerate(initial))
            if len(init) != 2 * n:
                raise ValueError(f"initial has {len(init)} entries; it must have 2n = {2 * n} "
                                 f"(n = {n} positions, m, then n velocities, m/s)")
            self.initial = init
        points = []
        for i, p in enumerate(speed_dependent):
            s, c, k = p
            points.append((_real(f"speed_dependent[{i}].speed", s),
                           None if c is None else _matrix(f"speed_dependent[{i}].damping", c),
                           None if k is None else _matrix(f"speed_dependent[{i}].stiffness", k)))
        self.speed_dependent: Tuple[Tuple[float, Optional[FloatArray], Optional[FloatArray]],
                                    ...] = tuple(points)
        self.name = str(name)
        self.reduction: Optional[Dict[str, Any]] = None if reduction is None else dict(reduction)
        _core.matrix_check(self._core_dict())

    # -- sources -------------------------------------------------------------------------------

    @classmethod
    def from_matrices(cls, M: Any, C: Any, K: Any, G: Any = None, *,
                      unbalance: Sequence[Unbalance] = (), rub: Rub, speed: float,
                      dofs: Optional[Sequence[str]] = None, phase: float = 0.0,
                      force: Optional[Sequence[float]] = None,
                      speed_dependent: Sequence[Tuple[float, Any, Any]] = (),
                      name: str = "") -> "Model":
        """A model from its matrices (numpy arrays, SI): M (kg; kg·m² on rotations), C (N·s/m),
        K (N/m; may be non-symmetric: cross-coupled bearings), G (gyroscopic, multiplied by the
        speed: C + ΩG; None for none); ``unbalance`` a list of ``(dof_x, dof_y, m_e, phase)``
        (the force m_e Ω² (cos(Ωt + phase), sin(Ωt + phase)) on the pair); ``rub`` a
        :class:`Rub`; ``speed`` Ω in rad/s. Optional: ``dofs`` (names), ``phase`` (the forcing
        phase at t = 0), ``force`` (a constant force per DOF, N), ``speed_dependent`` (a list of
        ``(speed, C or None, K or None)`` for sweeps and run-ups: C and K interpolated in the
        speed), ``name``. Raises ValueError naming the value and what is valid."""
        return cls(M=M, C=C, K=K, G=G, unbalance=unbalance, rub=rub, speed=speed, dofs=dofs,
                   phase=phase, force=force, speed_dependent=speed_dependent, name=name)

    @classmethod
    def from_file(cls, path: Union[str, "os.PathLike[str]"]) -> "Model":
        """A model file (TOML or ``.npz``, docs/MODEL_FILES.md): the same model as
        ``rotor-rub check-model FILE`` reads."""
        d = _core.matrix_load(os.fspath(path))
        initial = d["initial"]
        return cls(M=d["M"], C=d["C"], K=d["K"], G=d["G"], unbalance=d["unbalance"],
                   rub=Rub(**{k: v for k, v in d["rub"].items()}), speed=d["speed"],
                   dofs=d["dofs"], phase=d["phase"], force=d["force"],
                   initial=None if initial is None else list(initial[0]) + list(initial[1]),
                   speed_dependent=d["speed_dependent"], name=d["name"])

    @classmethod
    def from_ross(cls, rotor: Any, *, node: int, clearance: float, contact_stiffness: Stiffness,
                  friction_coefficient: float = 0.0, speed: Optional[float] = None,
                  modes: Optional[int] = None, unbalance: Sequence[Tuple[int, float, float]] = (),
                  radius: Optional[float] = None, offset: Tuple[float, float] = (0.0, 0.0),
                  name: str = "") -> "Model":
        """A model from a ROSS rotor: its M, C, K, G at ``speed`` (rad/s) over the lateral DOFs
        (x, y, α, β of each node; the axial and torsional DOFs are dropped, after checking that
        they are decoupled), a rub at ``node`` (its x, y) against a fixed stator.

        ``rotor`` is a ``ross.Rotor``, or the path of an ``.npz`` written by
        ``scripts/ross/export_rotor.py`` (arrays M, C, K, G, dofs, nodes, speed; no ROSS needed;
        ``speed`` must then be the file's or None). ``unbalance``: ``(node, m_e, phase)``
        triples, kg·m and rad, ROSS's convention (the force m_e Ω² (cos(Ωt + phase),
        sin(Ωt + phase)) at the node's x, y). ``radius``: the shaft's radius at the rub (needed
        with friction).

        ``modes``: None keeps every lateral DOF (at most 64 DOFs in this build); a number m
        reduces the model by :func:`craig_bampton`: the rub node's and the unbalance nodes' x, y
        stay physical DOFs (the contact and the forcing act on them exactly, results name them),
        the rest is represented by its static response to them plus its m lowest
        fixed-interface modes. ``model.reduction`` records what was kept and the error on the
        first natural frequencies against the full model."""
        if modes is not None and (isinstance(modes, bool) or not isinstance(
                modes, (numbers.Integral, np.integer)) or int(modes) < 0):
            raise ValueError(f"modes = {modes!r} must be None (no reduction) or an integer ≥ 0")
        M, C, K, G, names, nodes, ross_speed = _ross_matrices(rotor, speed)
        nodes = np.asarray(nodes)
        known = sorted(set(int(v) for v in nodes))
        node = _dof("node", node)

        def pair(what: str, at: int) -> Tuple[int, int]:
            idx = np.nonzero(nodes == at)[0]
            if len(idx) < 2:
                raise ValueError(f"{what} = {at} is not a node of the rotor: the nodes are "
                                 f"{known[0]} … {known[-1]}")
            return int(idx[0]), int(idx[1])

        rub_pair = pair("node", node)
        ub = []
        for i, given_u in enumerate(unbalance):
            u: Tuple[Any, ...] = tuple(given_u)
            if len(u) != 3:
                raise ValueError(f"unbalance[{i}] = {u!r} must be (node, m_e, phase): a node, "
                                 "kg·m, rad")
            at = pair(f"unbalance[{i}] node", _dof(f"unbalance[{i}] node", u[0]))
            ub.append((at, _real(f"unbalance[{i}].m_e", u[1]), _real(f"unbalance[{i}].phase", u[2])))
        reduction = None
        if modes is not None:
            keep = [rub_pair[0], rub_pair[1]]
            for (x, y), _, _ in ub:
                for d in (x, y):
                    if d not in keep:
                        keep.append(d)
            full = (M, C, K, G)
            M, C, K, G, T = craig_bampton(M, C, K, G, keep, int(modes))
            names = [names[d] for d in keep] + [f"mode{i + 1}" for i in range(int(modes))]
            index = {d: i for i, d in enumerate(keep)}
            rub_pair = (index[rub_pair[0]], index[rub_pair[1]])
            ub = [((index[x], index[y]), me, ph) for (x, y), me, ph in ub]
            reduction = {"method": "craig-bampton", "physical": [names[i] for i in
                                                                 range(len(keep))],
                         "modes": int(modes), "full_dofs": full[0].shape[0],
                         "frequency_error": _frequency_error(full, (M, C, K, G), ross_speed)}
        elif M.shape[0] > 64:
            raise ValueError(f"the rotor has n = {M.shape[0]} lateral DOFs; this build holds at "
                             "most 64: pass modes=… to reduce it (e.g. modes=12)")
        rub = Rub(rub_pair[0], rub_pair[1], clearance, contact_stiffness, friction_coefficient,
                  radius, offset)
        return cls(M=M, C=C, K=K, G=G, rub=rub, speed=ross_speed, dofs=names,
                   unbalance=[(x, y, me, ph) for (x, y), me, ph in ub],
                   name=name or "ROSS rotor", reduction=reduction)

    # -- the model ------------------------------------------------------------------------------

    @property
    def n(self) -> int:
        """The number of degrees of freedom."""
        return int(self.M.shape[0])

    def modes(self) -> npt.NDArray[np.complex128]:
        """The eigenvalues λ of the first-order system at the running speed (1/s), smallest
        modulus first: natural frequency |λ| (rad/s), damping ratio −Re λ/|λ|; complex
        conjugate pairs for vibration modes (``rotor-rub check-model`` prints them)."""
        return _core.matrix_modes(self._core_dict())

    def natural_frequencies(self) -> FloatArray:
        """The damped natural frequencies Im λ of :meth:`modes` with Im λ > 0, rad/s, in order
        of |λ| (as ``rotor-rub check-model`` lists the modes)."""
        return _damped_frequencies(self.modes())

    def with_speed(self, speed: float) -> "Model":
        """The same model at another running speed (C and K re-evaluated there when the model
        has ``speed_dependent`` matrices)."""
        return Model(M=self.M, C=self.C, K=self.K, G=self.G, unbalance=self.unbalance,
                     rub=self.station, speed=speed, dofs=self.dofs, phase=self.phase,
                     force=self.force, initial=self.initial,
                     speed_dependent=self.speed_dependent, name=self.name,
                     reduction=self.reduction)

    def columns(self) -> List[str]:
        """The state columns of this model's results: the DOFs, their velocities (``v`` +
        name), the rub station's relative displacement ``rub_x``, ``rub_y`` (m)."""
        return list(self.dofs) + [f"v{d}" for d in self.dofs] + ["rub_x", "rub_y"]

    def save(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Write the model as a self-contained ``.npz`` model file (docs/MODEL_FILES.md), which
        ``rotor-rub simulate --model`` and :meth:`from_file` read."""
        s = self.station
        rub = [s.dof_x, s.dof_y] + ([] if s.stator is None else list(s.stator))
        arrays: Dict[str, Any] = dict(
            M=self.M, C=self.C, G=self.G, K=self.K, dofs=np.array(self.dofs),
            speed=np.array(self.speed), phase=np.array(self.phase),
            rub=np.array(rub, dtype=np.float64), clearance=np.array(s.clearance),
            contact_stiffness=np.array(_stiffness(s.contact_stiffness)),
            friction_coefficient=np.array(s.friction_coefficient),
            offset=np.array(s.offset, dtype=np.float64))
        if self.unbalance:
            arrays["unbalance"] = np.array(self.unbalance, dtype=np.float64)
        if s.radius is not None:
            arrays["radius"] = np.array(s.radius)
        if self.force is not None:
            arrays["force"] = np.array(self.force)
        if self.initial is not None:
            arrays["initial"] = np.array(self.initial)
        if self.speed_dependent:
            n = self.n
            arrays["speeds"] = np.array([p[0] for p in self.speed_dependent])
            arrays["C_speeds"] = np.array([self.C if c is None else c
                                           for _, c, _ in self.speed_dependent]).reshape(-1, n, n)
            arrays["K_speeds"] = np.array([self.K if k is None else k
                                           for _, _, k in self.speed_dependent]).reshape(-1, n, n)
        with open(os.fspath(path), "wb") as f:
            np.savez(f, **arrays)

    def _core_dict(self) -> Dict[str, Any]:
        init = None if self.initial is None else (list(self.initial[:self.n]),
                                                  list(self.initial[self.n:]))
        return {"name": self.name, "dofs": list(self.dofs), "M": self.M, "C": self.C,
                "G": self.G, "K": self.K, "speed": self.speed, "phase": self.phase,
                "unbalance": list(self.unbalance),
                "force": None if self.force is None else list(self.force),
                "rub": self.station._core(), "initial": init,
                "speed_dependent": list(self.speed_dependent)}

    def __repr__(self) -> str:
        s = self.station
        name = self.dofs.__getitem__
        where = f"({name(cast(int, s.dof_x))}, {name(cast(int, s.dof_y))})"
        against = "a fixed stator" if s.stator is None else \
            f"the stator point ({name(cast(int, s.stator[0]))}, {name(cast(int, s.stator[1]))})"
        red = "" if self.reduction is None else \
            f", reduced from {self.reduction['full_dofs']} DOFs ({self.reduction['method']})"
        label = f"{self.name!r}, " if self.name else ""
        return (f"<rotor_rub.Model {label}n = {self.n}{red}, speed {self.speed:g} rad/s, rub at "
                f"{where} against {against}, clearance {s.clearance:g} m, "
                f"{len(self.unbalance)} unbalance(s)>")

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Model):
            return NotImplemented
        same = (self.dofs == other.dofs and self.speed == other.speed
                and self.phase == other.phase and self.unbalance == other.unbalance
                and self.force == other.force and self.station == other.station
                and self.initial == other.initial and self.name == other.name
                and len(self.speed_dependent) == len(other.speed_dependent))
        return same and all(np.array_equal(a, b) for a, b in (
            (self.M, other.M), (self.C, other.C), (self.G, other.G), (self.K, other.K)))

    __hash__ = None  # type: ignore[assignment]

    def __getstate__(self) -> Dict[str, Any]:
        return dict(self.__dict__)

    def __setstate__(self, state: Dict[str, Any]) -> None:
        self.__dict__.update(state)
        for name in ("M", "C", "G", "K"):
            a = np.array(state[name], dtype=np.float64)
            a.setflags(write=False)
            self.__dict__[name] = a


def _ross_matrices(rotor: Any, speed: Optional[float]) -> Tuple[Any, ...]:
    """(M, C, K, G, names, nodes, speed) over the lateral DOFs of a ROSS rotor or its export."""
    if isinstance(rotor, (str, os.PathLike)):
        with np.load(os.fspath(rotor)) as d:
            missing = [k for k in ("M", "C", "K", "G", "dofs", "nodes", "speed") if k not in d]
            if missing:
                raise ValueError(f"{os.fspath(rotor)} is not a ROSS export (scripts/ross/"
                                 f"export_rotor.py): it lacks {', '.join(missing)}")
            file_speed = float(d["speed"])
            if speed is not None and not math.isclose(_real("speed", speed), file_speed,
                                                      rel_tol=1e-12):
                raise ValueError(f"speed = {speed} rad/s: the export holds the matrices at "
                                 f"{file_speed} rad/s only (leave speed=None, or export again)")
            return (d["M"], d["C"], d["K"], d["G"], [str(x) for x in d["dofs"]],
                    np.asarray(d["nodes"]), file_speed)
    if speed is None:
        raise ValueError("speed = None: give the running speed in rad/s (ROSS's matrices "
                         "depend on it)")
    speed = _real("speed", speed)
    for attr in ("M", "K", "C", "G", "number_dof", "ndof"):
        if not hasattr(rotor, attr):
            raise ValueError(f"rotor = {type(rotor).__name__}: not a ross.Rotor (it has no "
                             f"{attr}) nor the path of an export .npz")
    ndof = int(rotor.number_dof)
    lateral_local = {6: (0, 1, 3, 4), 4: (0, 1, 2, 3)}.get(ndof)
    if lateral_local is None:
        raise ValueError(f"rotor.number_dof = {ndof}: a ROSS node has 4 or 6 DOFs")
    M, K, C, G = (np.asarray(a, dtype=np.float64) for a in
                  (rotor.M(speed), rotor.K(speed), rotor.C(speed), rotor.G()))
    total = int(rotor.ndof)
    lateral = [i for i in range(total) if i % ndof in lateral_local]
    other = [i for i in range(total) if i % ndof not in lateral_local]
    for label, a in (("M", M), ("K", K), ("C", C), ("G", G)):
        if other and max(np.abs(a[np.ix_(lateral, other)]).max(),
                         np.abs(a[np.ix_(other, lateral)]).max()) != 0.0:
            raise ValueError(f"the rotor's {label} couples its lateral DOFs to its axial or "
                             "torsional ones: the rub model needs them decoupled")
    pick = np.ix_(lateral, lateral)
    label_of = dict(zip(lateral_local, ("x", "y", "alpha", "beta")))
    names = [f"{label_of[i % ndof]}_{i // ndof}" for i in lateral]
    nodes = np.array([i // ndof for i in lateral])
    return M[pick], C[pick], K[pick], G[pick], names, nodes, speed


def craig_bampton(M: Any, C: Any, K: Any, G: Any, keep: Sequence[int],
                  modes: int) -> Tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
    """Craig–Bampton reduction: the DOFs ``keep`` stay physical (boundary), the others are their
    static response to the boundary (constraint modes, −K_ii⁻¹ K_ib) plus the ``modes`` lowest
    fixed-interface modes (of the symmetric parts of K_ii and M_ii, mass-normalised). Returns the
    reduced (M, C, K, G) = Tᵀ(·)T and T (n × (len(keep) + modes)); C, G and a non-symmetric K
    are projected with the same T (G stays skew-symmetric). Exact for the static response at the
    kept DOFs; the dynamics converge as ``modes`` grows (``Model.reduction`` states the error on
    the first natural frequencies)."""
    M, C, K, G = (np.asarray(a, dtype=np.float64) for a in (M, C, K, G))
    n = M.shape[0]
    b = list(keep)
    i = [d for d in range(n) if d not in set(b)]
    if modes > len(i):
        raise ValueError(f"modes = {modes} is out of range: the rotor has {len(i)} DOFs besides "
                         f"the {len(b)} kept physical; it must be in [0, {len(i)}]")
    Kii, Kib = K[np.ix_(i, i)], K[np.ix_(i, b)]
    Mii = M[np.ix_(i, i)]
    psi = -np.linalg.solve(Kii, Kib)
    ks = 0.5 * (Kii + Kii.T)
    ms = 0.5 * (Mii + Mii.T)
    L = np.linalg.cholesky(ms)
    Linv = np.linalg.inv(L)
    w2, V = np.linalg.eigh(Linv @ ks @ Linv.T)
    phi = (Linv.T @ V)[:, np.argsort(w2)[:modes]]
    T = np.zeros((n, len(b) + modes))
    T[b, np.arange(len(b))] = 1.0
    T[np.ix_(i, range(len(b)))] = psi
    T[np.ix_(i, range(len(b), len(b) + modes))] = phi
    red = [T.T @ a @ T for a in (M, C, K, G)]
    red[0] = 0.5 * (red[0] + red[0].T)
    red[3] = 0.5 * (red[3] - red[3].T)
    return red[0], red[1], red[2], red[3], T


def _first_order_frequencies(M: Any, C: Any, K: Any, G: Any, speed: float) -> FloatArray:
    n = M.shape[0]
    A = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-np.linalg.solve(M, K), -np.linalg.solve(M, C + speed * G)]])
    return _damped_frequencies(np.linalg.eigvals(A))


def _damped_frequencies(lam: Any) -> FloatArray:
    """Im λ of the eigenvalues with Im λ > 0, in order of |λ| (a heavily damped high mode has a
    small Im λ: ordering by Im λ would put it first)."""
    lam = np.asarray(lam)
    lam = lam[lam.imag > 0]
    return np.asarray(lam[np.argsort(np.abs(lam), kind="stable")].imag, dtype=np.float64)


def _frequency_error(full: Tuple[Any, ...], reduced: Tuple[Any, ...], speed: float,
                     count: int = 6) -> List[Tuple[float, float, float]]:
    """The first ``count`` damped natural frequencies (rad/s) of the full and the reduced
    model at ``speed`` and their relative difference."""
    f = _first_order_frequencies(full[0], full[1], full[2], full[3], speed)
    r = _first_order_frequencies(reduced[0], reduced[1], reduced[2], reduced[3], speed)
    k = min(count, len(f), len(r))
    return [(float(f[j]), float(r[j]), float(abs(r[j] - f[j]) / f[j])) for j in range(k)]


# -- runs ------------------------------------------------------------------------------------------

from .results import Events, Problem, Run, Samples  # noqa: E402


@dataclass
class MatrixRun(Run):
    """A :class:`rotor_rub.Run` of a :class:`Model`, SI units: times in s, state columns
    ``columns`` (the DOFs in m or rad, their velocities, then ``rub_x``, ``rub_y``: the rub
    station's relative displacement, m); ``model`` is the model it ran."""

    columns: Tuple[str, ...] = ()
    model: Optional[Model] = None

    def column(self, name: str, where: str = "samples") -> FloatArray:
        """One state column of the samples (or ``where="events"``) by name."""
        if name not in self.columns:
            raise ValueError(f"column {name!r} is not a state column: they are "
                             f"{', '.join(self.columns)}")
        rows = self.samples if where == "samples" else self.events
        return rows.state[:, self.columns.index(name)]


def _run_of(r: Mapping[str, Any], model: Model, options: Mapping[str, Any]) -> MatrixRun:
    """The result of a matrix run from the compiled core's dict (the same assembly whether the
    events come from the propagator or from a test's synthetic list)."""
    time_free, time_contact, time_rolling = r["time_in"]
    return MatrixRun(
        events=Events(r["event_time"], r["event_kind"], r["event_state"]),
        samples=Samples(r["sample_time"], r["sample_state"], r["sample_regime"]),
        start_time=r["start_time"], end_time=r["end_time"], end_state=r["end_state"],
        time_free=time_free, time_contact=time_contact, time_rolling=time_rolling,
        contact_fraction=r["contact_fraction"], forcing_period=r["forcing_period"],
        elapsed=r["elapsed"], problem=Problem._of(r["problem"], "simulate", options),
        columns=tuple(r["columns"]), model=model)


def simulate_model(model: Model, *, t_end: Any = None, periods: Any = None,
                   method: Optional[str] = None, tol: Any = None,
                   contact_scheme: Optional[str] = None, step: Any = None, samples: Any = 1001,
                   initial: Optional[Sequence[float]] = None) -> MatrixRun:
    """``rotor_rub.simulate(model=…)``: see its doc."""
    if not isinstance(model, Model):
        raise ValueError(f"model = {model!r} must be a rotor_rub.Model (Model.from_matrices, "
                         "Model.from_file, Model.from_ross)")
    init = None
    if initial is not None:
        init = [_real(f"initial[{i}]", x) for i, x in enumerate(initial)]
    r = _core.simulate_matrix(model._core_dict(), t_end=t_end, periods=periods, method=method,
                              tol=tol, contact_scheme=contact_scheme, step=step,
                              samples=samples, initial=init)
    options = {"model": repr(model), "t_end": t_end, "periods": periods, "samples": samples,
               "initial": None if init is None else list(init)}
    return _run_of(r, model, options)
