"""Results as tables: pandas, xarray, and files (Parquet, NetCDF) that keep the metadata.

Every result is one or more tables of columns (numpy arrays) plus metadata (its
:class:`rotor_rub.Problem` and its scalars). The first table is the main one (a run's samples,
a sweep's rows, a run-up's forcing periods); the others are named (``event``, ``point``,
``jump``).

- ``to_pandas(table=None)``: one table as a DataFrame (the main one by default), the metadata in
  ``df.attrs["rotor_rub"]``.
- ``to_xarray()``: every table in one Dataset, each along its own dimension (the main table's
  variables unprefixed, the others' prefixed with the table's name), the metadata as JSON in
  ``ds.attrs["rotor_rub"]`` and the problem's parameters, method and version as attributes.
- ``save(path)``: ``.parquet`` (pyarrow) — all tables in one file, stacked, with a ``table``
  column naming each row's table (``pd.read_parquet`` reads it as it is); ``.nc`` (xarray with
  h5netcdf or netCDF4) — the Dataset of ``to_xarray``. Written to a temporary beside the target
  and renamed into place: a file is complete or absent; only a regular file is replaced (a
  symlink's target is written). :func:`load` reads either back, bit for bit.

pandas, xarray, pyarrow, h5netcdf are optional dependencies, imported when used; a missing one
raises ImportError naming what to install.
"""

from __future__ import annotations

import json
import os
import tempfile
from typing import (TYPE_CHECKING, Any, Callable, Dict, List, Literal, Mapping, Optional, Tuple,
                    Type, TypeVar)

import numpy as np

if TYPE_CHECKING:
    import pandas
    import xarray

#: name → columns (equal-length 1-D arrays).
Tables = Dict[str, Dict[str, np.ndarray]]

_REGISTRY: Dict[str, Type["Result"]] = {}
#: Bumped when the layout of saved files changes.
FORMAT = 1

T = TypeVar("T", bound="Result")


def _need(module: str, extra: str) -> Any:
    """Import an optional dependency, or say what to install."""
    import importlib

    try:
        return importlib.import_module(module)
    except ImportError as e:
        raise ImportError(
            f"this needs {module.split('.')[0]}: pip install 'rotor_rub[{extra}]' "
            f"(or pip install {module.split('.')[0]})") from e


class Result:
    """Tables, conversions and files for every result type (see the module documentation)."""

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        _REGISTRY[cls.__name__] = cls

    def _tables(self) -> Tuple[Tables, Dict[str, Any]]:
        """The result's tables (main first) and scalars (`rotor_rub._tables`)."""
        from ._tables import CONVERTERS

        return CONVERTERS[type(self)][0](self)

    @classmethod
    def _from_tables(cls: Type[T], tables: Tables, meta: Mapping[str, Any]) -> T:
        from ._tables import CONVERTERS

        result: T = CONVERTERS[cls][1](tables, meta)
        return result

    def _meta(self) -> Tuple[Tables, Dict[str, Any]]:
        tables, scalars = self._tables()
        problem = getattr(self, "problem")
        meta = {
            "format": FORMAT,
            "type": type(self).__name__,
            "problem": problem.to_dict(),
            "scalars": scalars,
            "tables": {name: {c: _dtype(v) for c, v in cols.items()}
                       for name, cols in tables.items()},
        }
        return tables, meta

    def to_pandas(self, table: Optional[str] = None) -> "pandas.DataFrame":
        """One table as a DataFrame (the main one unless ``table`` names another); the metadata
        (problem, scalars) in ``df.attrs["rotor_rub"]``."""
        pd = _need("pandas", "pandas")
        tables, meta = self._meta()
        name = next(iter(tables)) if table is None else table
        if name not in tables:
            raise ValueError(f"table: {name!r} is not one of {', '.join(tables)}")
        df = pd.DataFrame({c: v for c, v in tables[name].items()})
        df.attrs["rotor_rub"] = meta
        return df

    def to_xarray(self) -> "xarray.Dataset":
        """Every table in one Dataset (see the module documentation)."""
        xr = _need("xarray", "xarray")
        tables, meta = self._meta()
        main = next(iter(tables))
        data = {}
        for name, cols in tables.items():
            prefix = "" if name == main else name + "_"
            for c, v in cols.items():
                data[prefix + c] = (name, v)
        problem = meta["problem"]
        attrs: Dict[str, Any] = {
            "rotor_rub": json.dumps(meta),
            "rotor_rub_version": problem["version"],
            "call": problem["call"],
            "method": problem["method_text"],
        }
        attrs.update({f"param_{k}": float(v) for k, v in problem["params"].items()})
        dataset: "xarray.Dataset" = xr.Dataset(data, attrs=attrs)
        return dataset

    def save(self, path: "os.PathLike[str] | str", format: Optional[str] = None) -> None:
        """Write the result to ``path``: Parquet (``.parquet``) or NetCDF (``.nc``), or as
        ``format`` (``"parquet"``, ``"netcdf"``) says; the metadata included. Atomic: the file
        is complete or absent."""
        target = _target(os.fspath(path))
        kind = _format(target, format)
        if kind == "parquet":
            _atomic(target, lambda tmp: _write_parquet(self, tmp))
        else:
            _atomic(target, lambda tmp: _write_netcdf(self, tmp))


def _dtype(v: np.ndarray) -> str:
    return "str" if v.dtype.kind in "UO" else v.dtype.str


def _column(values: Any, dtype: str) -> np.ndarray:
    if dtype == "str":
        return np.asarray([str(x) for x in values], dtype=np.str_)
    return np.asarray(values).astype(np.dtype(dtype), copy=False)


def _target(path: str) -> str:
    """The file to write: `path`, a symlink's target; refused when it is not a regular file."""
    real = os.path.realpath(path)
    if os.path.exists(real) and not os.path.isfile(real):
        raise ValueError(f"path: {path} exists and is not a regular file; not replaced")
    return real


def _format(path: str, given: Optional[str]) -> str:
    if given is not None:
        if given not in ("parquet", "netcdf"):
            raise ValueError(f"format: {given!r} is not 'parquet' or 'netcdf'")
        return given
    ext = os.path.splitext(path)[1].lower()
    if ext in (".parquet", ".pq"):
        return "parquet"
    if ext in (".nc", ".nc4", ".netcdf", ".h5"):
        return "netcdf"
    raise ValueError(f"path: {path} ends in {ext or 'no extension'}: use .parquet or .nc, "
                     "or give format='parquet' or 'netcdf'")


def _atomic(path: str, write: Callable[[str], None]) -> None:
    directory = os.path.dirname(path) or "."
    fd, tmp = tempfile.mkstemp(prefix=".rotor-rub-", suffix=os.path.splitext(path)[1],
                               dir=directory)
    os.close(fd)
    try:
        write(tmp)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def _write_parquet(result: Result, path: str) -> None:
    pa = _need("pyarrow", "parquet")
    pq = _need("pyarrow.parquet", "parquet")
    tables, meta = result._meta()
    parts = []
    for name, cols in tables.items():
        n = len(next(iter(cols.values()))) if cols else 0
        arrays = {"table": pa.array([name] * n, pa.string())}
        arrays.update({c: pa.array(v) for c, v in cols.items()})
        parts.append(pa.table(arrays))
    try:
        stacked = pa.concat_tables(parts, promote_options="default")
    except TypeError:  # pyarrow < 14
        stacked = pa.concat_tables(parts, promote=True)
    stacked = stacked.replace_schema_metadata({"rotor_rub": json.dumps(meta)})
    pq.write_table(stacked, path)


def _write_netcdf(result: Result, path: str) -> None:
    ds = result.to_xarray()
    ds.to_netcdf(path, engine=_netcdf_engine())


def _netcdf_engine() -> Literal["h5netcdf", "netcdf4"]:
    import importlib.util

    if importlib.util.find_spec("h5netcdf") is not None and \
            importlib.util.find_spec("h5py") is not None:
        return "h5netcdf"
    if importlib.util.find_spec("netCDF4") is not None:
        return "netcdf4"
    raise ImportError("NetCDF files need xarray with h5netcdf (and h5py) or netCDF4: "
                      "pip install 'rotor_rub[xarray]'")


def load(path: "os.PathLike[str] | str") -> Result:
    """A result saved by ``.save(path)`` (Parquet or NetCDF), with its problem and metadata,
    bit for bit."""
    path = os.fspath(path)
    with open(path, "rb") as f:
        head = f.read(8)
    if head[:4] == b"PAR1":
        tables, meta = _read_parquet(path)
    elif head[:4] in (b"\x89HDF", b"CDF\x01", b"CDF\x02"):
        tables, meta = _read_netcdf(path)
    else:
        raise ValueError(f"path: {path} is neither a Parquet nor a NetCDF file")
    if meta.get("format") != FORMAT or meta.get("type") not in _REGISTRY:
        raise ValueError(f"path: {path} was not saved by rotor_rub's save (format "
                         f"{meta.get('format')}, type {meta.get('type')})")
    return _REGISTRY[meta["type"]]._from_tables(tables, meta)


def _meta_of(text: Any, path: str) -> Dict[str, Any]:
    if text is None:
        raise ValueError(f"path: {path} has no rotor_rub metadata (not saved by rotor_rub)")
    meta: Dict[str, Any] = json.loads(text)
    return meta


def _read_parquet(path: str) -> Tuple[Tables, Dict[str, Any]]:
    pq = _need("pyarrow.parquet", "parquet")
    pc = _need("pyarrow.compute", "parquet")
    stacked = pq.read_table(path)
    meta = _meta_of((stacked.schema.metadata or {}).get(b"rotor_rub"), path)
    tables: Tables = {}
    for name, spec in meta["tables"].items():
        part = stacked.filter(pc.equal(stacked.column("table"), name))
        tables[name] = {c: _column(part.column(c).to_pylist() if dtype == "str"
                                   else part.column(c).to_numpy(zero_copy_only=False), dtype)
                        for c, dtype in spec.items()}
    return tables, meta


def _read_netcdf(path: str) -> Tuple[Tables, Dict[str, Any]]:
    xr = _need("xarray", "xarray")
    ds = xr.load_dataset(path, engine=_netcdf_engine())
    meta = _meta_of(ds.attrs.get("rotor_rub"), path)
    main = next(iter(meta["tables"]))
    tables: Tables = {}
    for name, spec in meta["tables"].items():
        prefix = "" if name == main else name + "_"
        tables[name] = {c: _column(ds[prefix + c].values, dtype) for c, dtype in spec.items()}
    return tables, meta


def split_state(state: np.ndarray) -> Dict[str, np.ndarray]:
    """(n, 4) states as columns x, y, vx, vy."""
    return {c: np.ascontiguousarray(state[:, j]) for j, c in enumerate(("x", "y", "vx", "vy"))}


def join_state(cols: Mapping[str, np.ndarray]) -> np.ndarray:
    """Columns x, y, vx, vy as (n, 4) states."""
    return np.stack([cols[c] for c in ("x", "y", "vx", "vy")], axis=1).reshape(-1, 4)


def codes(names: np.ndarray, table: Tuple[str, ...]) -> np.ndarray:
    """Names as uint8 indices into `table`."""
    lookup = {n: i for i, n in enumerate(table)}
    return np.array([lookup[str(n)] for n in names], dtype=np.uint8)


__all__: List[str] = ["Result", "load", "split_state", "join_state", "codes"]
