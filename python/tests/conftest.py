"""Shared fixtures: the `rotor-rub` CLI binary (results and messages are compared with it)."""

from __future__ import annotations

import csv
import os
import subprocess
from pathlib import Path
from typing import Dict, List, Sequence, Tuple

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


def _find_cli() -> Path:
    given = os.environ.get("ROTOR_RUB_CLI")
    if given:
        return Path(given)
    for profile in ("debug", "release"):
        candidate = ROOT / "target" / profile / "rotor-rub"
        if candidate.is_file():
            return candidate
    subprocess.run(["cargo", "build", "-q", "-p", "rotor-rub-cli"], cwd=ROOT, check=True)
    return ROOT / "target" / "debug" / "rotor-rub"


@pytest.fixture(scope="session")
def cli() -> Path:
    return _find_cli()


def run_cli(cli: Path, args: Sequence[str], cwd: Path, code: int = 0) -> subprocess.CompletedProcess:
    out = subprocess.run([str(cli), *args], cwd=cwd, capture_output=True, text=True)
    assert out.returncode == code, (out.returncode, out.stderr)
    return out


def read_csv(path: Path) -> Tuple[List[str], List[List[str]]]:
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    return rows[0], rows[1:]


def columns(path: Path) -> Dict[str, np.ndarray]:
    """A CSV's columns: numbers as float64 (parsed from the shortest round-trip text, so exact),
    other columns as strings."""
    header, rows = read_csv(path)
    out: Dict[str, np.ndarray] = {}
    for j, name in enumerate(header):
        values = [r[j] for r in rows]
        try:
            out[name] = np.array([float(v) for v in values], dtype=np.float64)
        except ValueError:
            out[name] = np.array(values)
    return out


def cli_error(cli: Path, args: Sequence[str], cwd: Path) -> str:
    """The CLI's message for invalid input (exit 2), without the `error: ` prefix."""
    out = run_cli(cli, args, cwd, code=2)
    line = out.stderr.strip().splitlines()[0]
    assert line.startswith("error: "), out.stderr
    return line[len("error: "):]


#: The CLI's flags and the Python keywords that say the same (python/src/errors.rs).
KEYWORD_OF_FLAG = [
    ("--samples-per-period", "samples_per_period"), ("--sample-count", "samples"),
    ("--contact-scheme", "contact_scheme"), ("--speed-holds", "speed_holds"),
    ("--ramp-periods", "ramp_periods"), ("--max-work", "max_work"),
    ("--transient", "transient"), ("--periods", "periods"), ("--profile", "profile"),
    ("--method", "method"), ("--config", "config"), ("--settle", "settle"),
    ("--dwell", "dwell"), ("--t-end", "t_end"), ("--keep", "keep"), ("--step", "step"),
    ("--tol", "tol"),
]


def as_keywords(message: str) -> str:
    """A CLI message as Python says it: keywords where the CLI names flags, "keyword
    arguments" where it says --set."""
    import re

    message = message.replace("(from --set)", "(from keyword arguments)")
    for flag, keyword in KEYWORD_OF_FLAG:
        message = re.sub(re.escape(flag) + r"(?![\w-])", keyword, message)
    return message
