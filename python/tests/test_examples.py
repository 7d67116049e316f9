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


def blocks(page: str, marker: str) -> list[str]:
    """The ```python blocks that follow each `marker` in `page`."""
    out = []
    for block in page.split(marker)[1:]:
        code = block[block.index("```python\n") + 10:]
        out.append(code[:code.index("```")])
    return out


def test_the_ring_preset_examples_run(monkeypatch, tmp_path: Path) -> None:
    """Issue 28 item 7: README's and docs/PYTHON.md's ring-preset examples, as shown."""
    import matplotlib

    matplotlib.use("Agg")
    monkeypatch.chdir(tmp_path)
    readme = blocks((ROOT / "README.md").read_text(), "<!-- readme: ring example")
    docs = blocks((ROOT / "docs" / "PYTHON.md").read_text(), "<!-- ring-example -->")
    assert len(readme) == 1 and len(docs) == 1
    for code in readme + docs:
        exec(compile(code, "example", "exec"), {})


def test_the_ring_presets_example_runs(tmp_path: Path) -> None:
    out = subprocess.run([sys.executable, str(EXAMPLES / "ring_presets.py"),
                          str(tmp_path / "ring.png")],
                         capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    assert "stator-mass: after 50 periods" in out.stdout, out.stdout
    assert "ring-whirl: after 90 periods 0 contact starts, in contact 100%" in out.stdout, out.stdout
    assert (tmp_path / "ring.png").is_file()
