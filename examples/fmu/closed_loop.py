"""A PD controller closing the loop around the rotor–stator FMU (FMI 3.0, or 2.0) with FMPy.

The controller measures x, y, x', y' after every communication step and sets the external force
fx, fy for the next one (held constant over the step, as a magnetic bearing's amplifier holds its
current):  f = -kp (q - q_ref) - kd q',  q_ref = the stator centre (the paper preset's offset).
It stiffens and damps the rotor and pulls its orbit towards the middle of the clearance, so it
rubs far less than the open loop.

    cargo xtask fmu
    python examples/fmu/closed_loop.py                  # prints the contact counts, writes out/closed_loop.png
    python examples/fmu/closed_loop.py --fmu target/fmu/rotor_rub_fmi2.fmu --periods 40

The same function serves the test (fmu/tests/test_fmu.py).
"""

from __future__ import annotations

import argparse
import math
import shutil
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave

ROOT = Path(__file__).resolve().parents[2]
DEFAULT_FMU = ROOT / "target" / "fmu" / "rotor_rub_fmi3.fmu"


@dataclass
class Run:
    """One co-simulation: sampled time, states (n, 4), forces (n, 2) and the contact count."""

    time: np.ndarray
    state: np.ndarray
    force: np.ndarray
    contact_count: int


def simulate(fmu: Path, kp: float, kd: float, periods: float = 20.0, step: float = 1e-3) -> Run:
    """Co-simulate the paper preset for `periods` forcing periods with communication step `step`;
    kp = kd = 0 is the open loop."""
    md = read_model_description(str(fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    unzipped = extract(str(fmu))
    fmi3 = md.fmiVersion.startswith("3")
    cls = FMU3Slave if fmi3 else FMU2Slave
    slave = cls(guid=md.guid, unzipDirectory=unzipped,
                modelIdentifier=md.coSimulation.modelIdentifier, instanceName="rotor")
    try:
        slave.instantiate()
        get = slave.getFloat64 if fmi3 else slave.getReal
        put = slave.setFloat64 if fmi3 else slave.setReal
        geti = slave.getInt64 if fmi3 else slave.getInteger
        if fmi3:
            slave.enterInitializationMode(startTime=0.0)
        else:
            slave.setupExperiment(startTime=0.0)
            slave.enterInitializationMode()
        slave.exitInitializationMode()
        offset = get([vr["offset_x"], vr["offset_y"]])
        eta = get([vr["speed_ratio"]])[0]
        n = int(round(periods * 2 * math.pi / eta / step))
        states = [get([vr["x"], vr["y"], vr["vx"], vr["vy"]])]
        forces = []
        t = 0.0
        for k in range(n):
            x, y, vx, vy = states[-1]
            f = [-kp * (x - offset[0]) - kd * vx, -kp * (y - offset[1]) - kd * vy]
            put([vr["fx"], vr["fy"]], f)
            slave.doStep(currentCommunicationPoint=t, communicationStepSize=step)
            t = (k + 1) * step
            states.append(get([vr["x"], vr["y"], vr["vx"], vr["vy"]]))
            forces.append(f)
        count = int(geti([vr["contact_count"]])[0])
        slave.terminate()
    finally:
        slave.freeInstance()
        shutil.rmtree(unzipped, ignore_errors=True)
    return Run(np.arange(n + 1) * step, np.array(states), np.array(forces), count)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--fmu", type=Path, default=DEFAULT_FMU)
    parser.add_argument("--periods", type=float, default=20.0)
    parser.add_argument("--kp", type=float, default=0.5)
    parser.add_argument("--kd", type=float, default=1.0)
    parser.add_argument("--plot", type=Path, default=ROOT / "out" / "closed_loop.png")
    args = parser.parse_args()
    open_loop = simulate(args.fmu, 0.0, 0.0, args.periods)
    closed = simulate(args.fmu, args.kp, args.kd, args.periods)
    print(f"contact entries over {args.periods:g} periods: open loop {open_loop.contact_count}, "
          f"PD (kp = {args.kp:g}, kd = {args.kd:g}) {closed.contact_count}")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (orbit, force) = plt.subplots(1, 2, figsize=(10, 4.5))
    circle = np.linspace(0, 2 * np.pi, 400)
    ox, oy = 0.3, -0.2
    orbit.plot(ox + np.cos(circle), oy + np.sin(circle), "k-", lw=1, label="clearance")
    orbit.plot(open_loop.state[:, 0], open_loop.state[:, 1], lw=0.6,
               label=f"open loop ({open_loop.contact_count} contacts)")
    orbit.plot(closed.state[:, 0], closed.state[:, 1], lw=0.6,
               label=f"PD control ({closed.contact_count} contacts)")
    orbit.set_aspect("equal")
    orbit.set_xlabel("x")
    orbit.set_ylabel("y")
    orbit.legend(loc="lower left", fontsize=8)
    orbit.set_title("paper preset, 20 periods, FMU + FMPy")
    force.plot(closed.time[1:], closed.force[:, 0], lw=0.6, label="fx")
    force.plot(closed.time[1:], closed.force[:, 1], lw=0.6, label="fy")
    force.set_xlabel("τ")
    force.set_ylabel("controller force")
    force.legend(fontsize=8)
    fig.tight_layout()
    args.plot.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.plot, dpi=110)
    print(f"wrote {args.plot}")


if __name__ == "__main__":
    main()
