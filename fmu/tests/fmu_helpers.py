"""Shared by the FMU tests: where the FMUs are, and an FMI 3.0 / 2.0 instance through FMPy's
low-level classes, initialized and ready to step (with every logged message kept)."""

from __future__ import annotations

import os
import shutil
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave

ROOT = Path(__file__).resolve().parents[2]
FMU_DIR = Path(os.environ.get("ROTOR_RUB_FMU_DIR", ROOT / "target" / "fmu"))
FMUS = {"3.0": FMU_DIR / "rotor_rub_fmi3.fmu", "2.0": FMU_DIR / "rotor_rub_fmi2.fmu"}
SI_FMUS = {"3.0": FMU_DIR / "rotor_rub_si_fmi3.fmu", "2.0": FMU_DIR / "rotor_rub_si_fmi2.fmu"}
ALL_FMUS = {f"{p.stem}": p for p in [*FMUS.values(), *SI_FMUS.values()]}


@dataclass
class Instance:
    """An FMU instance through FMPy: `slave`, value references by name, the log."""

    slave: Any
    vr: dict[str, int]
    unzipped: str
    messages: list[str] = field(default_factory=list)

    def close(self) -> None:
        self.slave.freeInstance()
        shutil.rmtree(self.unzipped, ignore_errors=True)


def instance(fmu: Path, early_return: bool = False, start: dict[str, float] | None = None,
             initialize: bool = True) -> Instance:
    """An instance of `fmu` with `start` values set before initialization (FMI 3.0 or 2.0;
    messages are kept for FMI 3.0 only)."""
    md = read_model_description(str(fmu))
    unzipped = extract(str(fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    messages: list[str] = []
    fmi3 = md.fmiVersion.startswith("3")
    cls = FMU3Slave if fmi3 else FMU2Slave
    slave = cls(guid=md.guid, unzipDirectory=unzipped,
                modelIdentifier=md.coSimulation.modelIdentifier, instanceName="test")
    if fmi3:
        def log3(env, status, category, message) -> None:  # type: ignore[no-untyped-def]
            messages.append(message.decode())
        slave.instantiate(earlyReturnAllowed=early_return, logMessage=log3)
    else:
        # FMI 2.0's logger is variadic (a printf format): FMPy's default prints it.
        slave.instantiate()
    result = Instance(slave, vr, unzipped, messages)
    for name, value in (start or {}).items():
        set_real(result, name, value)
    if initialize:
        if fmi3:
            slave.enterInitializationMode(startTime=0.0)
        else:
            slave.setupExperiment(startTime=0.0)
            slave.enterInitializationMode()
        slave.exitInitializationMode()
    return result


def set_real(i: Instance, name: str, value: float) -> None:
    put = getattr(i.slave, "setFloat64", None) or i.slave.setReal
    put([i.vr[name]], [value])


def get_real(i: Instance, names: list[str]) -> list[float]:
    get = getattr(i.slave, "getFloat64", None) or i.slave.getReal
    return list(get([i.vr[n] for n in names]))
