"""The stubs and annotations hold: mypy --strict passes on the example and the package."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


EXAMPLES = [ROOT / "examples" / "python" / name
            for name in ("quickstart.py", "dask_sweep.py", "ring_presets.py")]


def test_mypy_strict_on_the_examples() -> None:
    """The examples use numpy scalars, integer arrays and every new call: typed by the stubs."""
    out = subprocess.run(
        [sys.executable, "-m", "mypy", "--strict", "--no-incremental", *map(str, EXAMPLES)],
        capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 0, out.stdout + out.stderr


def test_mypy_strict_on_the_package() -> None:
    """The package's own annotations and the stubs of its compiled core agree."""
    out = subprocess.run(
        [sys.executable, "-m", "mypy", "--strict", "--no-incremental", "rotor_rub"],
        capture_output=True, text=True, cwd=ROOT / "python")
    assert out.returncode == 0, out.stdout + out.stderr


def test_stubs_match_the_compiled_core(tmp_path: Path) -> None:
    """mypy's stubtest: every function, class and parameter of _core.pyi against the module
    (run outside the source tree, so the installed package is what is imported)."""
    out = subprocess.run([sys.executable, "-m", "mypy.stubtest", "rotor_rub._core"],
                         capture_output=True, text=True, cwd=tmp_path)
    assert out.returncode == 0, out.stdout + out.stderr


def test_a_type_error_is_caught() -> None:
    """The check can fail: a wrong call is reported."""
    bad = "import rotor_rub as rr\nrun: rr.Section = rr.simulate(periods='many')\n"
    out = subprocess.run([sys.executable, "-m", "mypy", "--strict", "--no-incremental", "-c", bad],
                         capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 1, out.stdout
    assert "periods" in out.stdout or "incompatible" in out.stdout.lower()
