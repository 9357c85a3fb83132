"""What the PyElastica peer scripts (`pyelastica_free.py`, `pyelastica_drag.py`) share: the
command line's options, the unit rod as a PyElastica Cosserat rod, and its explicit step.

The unit rod is vibrissa's (EI = 1, rho*A = 1, L = 1) with a circular section of radius r:
I = pi r^4 / 4, A = pi r^2, E = 1/I, rho = 1/A (PyElastica's default shear modulus, nu = 0.5).
"""

import math
import sys

import numpy as np
import elastica as ea


def option(name, default):
    """The comma-separated values after `name` on the command line, or `default`."""
    if name in sys.argv:
        return [float(v) for v in sys.argv[sys.argv.index(name) + 1].split(",")]
    return default


def unit_rod(n, r, direction, normal):
    """The straight unit rod of n elements and radius r from the origin along `direction`."""
    area = math.pi * r * r
    inertia = math.pi * r**4 / 4.0
    return ea.CosseratRod.straight_rod(
        n,
        np.zeros(3),
        np.array(direction, dtype=float),
        np.array(normal, dtype=float),
        1.0,
        r,
        1.0 / area,
        youngs_modulus=1.0 / inertia,
    )


def stable_dt(r, n):
    """PositionVerlet's step for the unit rod: below the shear-rotation wave's bound 0.87 r^2
    (0.4 r^2) and the axial wave's dx r / 2 (half of it)."""
    return min(0.4 * r * r, 0.5 * (1.0 / n) * r / 2.0)
