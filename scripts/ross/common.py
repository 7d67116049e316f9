"""What the ROSS scripts share: the rotor, the rub and the run of ROSS's rubbing tutorial.

The rotor is ``ross.rotor_example_with_damping()`` (33 steel shaft elements, disks at nodes 12 and
24, bearings at nodes 4 and 31, Rayleigh damping), the one ROSS's rubbing fault is documented on
(``ross.faults.rubbing.rubbing_example``, ``Rotor.run_rubbing``'s example): the rub on shaft
element 12 (its left node, node 12, carries disk 0), clearance 7.95e-5 m, contact stiffness
1.1e6 N/m, unbalance 2e-4 kg·m at node 12, phase −π/2, 1200 rpm, time step 1e-4 s.

The tutorial's clearance is never reached: the rub node's unbalance response peaks at
5.37e-5 m over 10 periods at steps 1e-4 and 5e-5 s (ROSS's own run, no contact at all). The
scripts use δ = 4.0e-5 m, which the free whirl exceeds by a third, so the rotor rubs.

For a like-for-like comparison with rotor-rub the rub is frictionless and without contact
damping: ROSS's friction (a per-component ``μ|F|`` with signs from the slip's sign) and its
contact damping (``−c ẏ |ẏ|/|ẏ|``) are laws rotor-rub does not state, while its elastic contact
force ``−k (r − δ) y/r`` is rotor-rub's with K_c = k I and a centred stator.
"""

import json
import os
import platform
import sys
import warnings

import numpy as np

warnings.filterwarnings("ignore")

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.normpath(os.path.join(HERE, "..", "..", "tests", "data", "ross"))

RUB_ELEMENT = 12          # ROSS's shaft element with the rub; its left node is node 12
RUB_NODE = 12
TUTORIAL_CLEARANCE = 7.95e-5  # m: the tutorial's; its unbalance response never reaches it
CLEARANCE = 4.0e-5        # m: the rub node's free whirl is 5.37e-5 m (run_rubbing.py at 7.95e-5)
CONTACT_STIFFNESS = 1.1e6  # N/m
CONTACT_DAMPING = 0.0     # N·s/m (the tutorial's 40: see the module's docs)
FRICTION = 0.0            # (the tutorial's 0.3: see the module's docs)
UNBALANCE_NODE = 12
UNBALANCE = 2e-4          # kg·m
UNBALANCE_PHASE = -np.pi / 2
SPEED_RPM = 1200.0
SPEED = SPEED_RPM * 2 * np.pi / 60   # rad/s
PERIOD = 2 * np.pi / SPEED           # s
DEFAULT_STEP = 1e-4       # s: the tutorial's time step
#: The lateral DOFs of a 6-DOF node, in ROSS's order: x, y, α (θx), β (θy); z and θ (axial,
#: torsion) are decoupled from them in this rotor (checked on export) and dropped.
LATERAL = (0, 1, 3, 4)
LATERAL_NAMES = ("x", "y", "alpha", "beta")


def rotor():
    import ross as rs

    return rs.rotor_example_with_damping()


def versions():
    import ross
    import scipy

    return {"ross": ross.__version__, "numpy": np.__version__, "scipy": scipy.__version__,
            "python": sys.version.split()[0], "platform": platform.platform()}


def write_json(name, data):
    path = os.path.join(DATA, name)
    with open(path, "w") as f:
        json.dump(data, f, indent=1, sort_keys=True)
        f.write("\n")
    return path
