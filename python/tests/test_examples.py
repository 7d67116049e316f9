"""The examples run as saved scripts, and docs/PYTHON.md shows the Dask one as it is."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples" / "python"


def test_the_docs_show_the_dask_example_as_it_is() -> None:
    page = (ROOT / "docs" / "PYTHON.md").read_text()
    marker = "<!-- example: examples/python/dask_sweep.py -->\n```python\n"
    shown = page[page.index(marker) + len(marker):]
    shown = shown[:shown.index("```")]
    assert shown == (EXAMPLES / "dask_sweep.py").read_text()
    assert 'if __name__ == "__main__":' in shown


def test_the_dask_example_runs_as_a_script(tmp_path: Path) -> None:
    """Issue 33 item 4: run as a file, with worker processes that import it (spawn), under its
    main guard; the result equals the single-machine sweep (the script asserts it)."""
    store = tmp_path / "store"
    out = subprocess.run([sys.executable, str(EXAMPLES / "dask_sweep.py"), str(store)],
                         capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    assert "period-1" in out.stdout and (store / "sweep.json").is_file()


def test_the_quickstart_runs(tmp_path: Path) -> None:
    out = subprocess.run([sys.executable, str(EXAMPLES / "quickstart.py"), str(tmp_path)],
                         capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    assert "up jump at η = 2.474" in out.stdout and (tmp_path / "sweep.parquet").is_file()
