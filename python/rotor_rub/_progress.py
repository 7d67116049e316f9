"""The ``progress=`` option of the long calls: None (no report), True (a tqdm bar when tqdm is
installed, else a one-line counter on stderr), a tqdm-style bar (anything with ``update``: its
total is set when it has none, it is advanced and left open for its owner) or a callable
``progress(done, total)``. The compiled core reports about every 50 ms of work and once at the
end."""

from __future__ import annotations

import sys
from typing import Any, Callable, Optional, Tuple

Report = Callable[[float, float], None]


class _Counter:
    """The fallback bar: ``desc: done/total unit`` rewritten in place on stderr."""

    def __init__(self, desc: str, unit: str) -> None:
        self.desc, self.unit = desc, unit

    def __call__(self, done: float, total: float) -> None:
        sys.stderr.write(f"\r{self.desc}: {done:.0f}/{total:.0f} {self.unit}")
        sys.stderr.flush()

    def close(self) -> None:
        sys.stderr.write("\n")


class _Bar:
    """A tqdm-style bar driven by (done, total) reports."""

    def __init__(self, bar: Any, whole: bool) -> None:
        self.bar, self.whole, self.shown = bar, whole, 0.0

    def __call__(self, done: float, total: float) -> None:
        if getattr(self.bar, "total", None) is None:
            self.bar.total = int(round(total)) if self.whole else total
        done = float(int(done)) if self.whole else done
        if done > self.shown:
            self.bar.update(int(done - self.shown) if self.whole else done - self.shown)
            self.shown = done


def reporter(progress: Any, desc: str, unit: str, whole: bool = True
             ) -> Tuple[Optional[Report], Callable[[], None]]:
    """The core's callback for ``progress`` and what closes it after the call."""
    if progress is None or progress is False:
        return None, lambda: None
    if progress is True:
        try:
            from tqdm.auto import tqdm
        except ImportError:
            counter = _Counter(desc, unit)
            return counter, counter.close
        bar = tqdm(total=None, desc=desc, unit=unit)
        return _Bar(bar, whole), bar.close
    if hasattr(progress, "update"):
        return _Bar(progress, whole), lambda: None
    if callable(progress):
        report: Report = progress
        return report, lambda: None
    raise ValueError(f"progress: {progress!r} is not None, True, a callable "
                     "progress(done, total) or a tqdm-style bar")


def run(call: Callable[[Optional[Report]], Any], progress: Any, desc: str, unit: str,
        whole: bool = True) -> Any:
    """``call(report)`` with ``progress`` turned into a report, closed afterwards."""
    report, close = reporter(progress, desc, unit, whole)
    try:
        return call(report)
    finally:
        close()
