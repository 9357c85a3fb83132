#!/usr/bin/env python3
"""Independent reference points of the stiction scan for crate `vibrissa` (tests/reference.rs).

For each scene the rod equations (normalized units, arc length s from the foot)

    x' = cos(phi),  y' = sin(phi),  phi' = k0(s) + b(s) m,  m' = f cos(phi - alpha)
    x(0) = y(0) = 0,  phi(0) = pi/2 + c m(0)

are integrated by scipy's DOP853 (`solve_ivp`, rtol 1e-13, atol 1e-15: none of the crate's code)
and Powell's hybrid method (`scipy.optimize.root`, `hybr`, xtol 1e-15) solves

    start:      alpha = beta,  m(1) = 0, y(1) = eta                      -> x* = x(1)
    scan point: m(1) = 0, x(1) = x* - d, y(1) = eta  (unknowns m(0), f, alpha)
    lift-off:   alpha = beta - pi/2 (normal force 0), m(1) = 0, y(1) = eta  -> d = x* - x(1)

The branch is fixed by the starting guesses, which come from the program itself
(`vibrissa scan`, release build): they only seed the root finder; every answer is checked to a
residual below 1e-12. Accuracy: halving the integrator tolerances changes the values by less than
about 1e-11 (checked by the script: it solves every point at rtol 1e-13 and 1e-12 and reports the
largest difference), so the tests compare at 1e-8. Printed with 17 significant digits.
Run from the workspace root after `cargo build --release`:

    pip install scipy; python3 data/vibrissa/make_reference.py   (about a minute)
"""
import csv
import subprocess
import sys

import numpy as np
from numpy import cos, sin, pi
from scipy.integrate import solve_ivp
from scipy.optimize import root

BIN = "target/release/vibrissa"
RTOL = 1e-13

# name, flags, b(s), k0(s), c, eta, beta, displacements
SCENES = [
    ("uniform", [], lambda s: 1, lambda s: 0, 0, 0.75, 0.0, [0.05, 0.13, 0.3, 0.45]),
    ("taper 0.7", ["--taper", "0.7"], None, lambda s: 0, 0, 0.75, 0.0, [0.05, 0.1, 0.15]),
    ("taper 0.3 eta 0.9", ["--taper", "0.3", "--eta", "0.9"], None, lambda s: 0, 0, 0.9, 0.0,
     [0.05, 0.15, 0.3]),
    ("taper 0.1 eta 0.97", ["--taper", "0.1", "--eta", "0.97"], None, lambda s: 0, 0, 0.97, 0.0,
     [0.02, 0.08, 0.15]),
    ("k0 +1", ["--precurvature", "1"], lambda s: 1, lambda s: 1, 0, 0.75, 0.0, [0.05, 0.15, 0.3]),
    ("k0 -1", ["--precurvature=-1"], lambda s: 1, lambda s: -1, 0, 0.75, 0.0, [0.05, 0.1, 0.2]),
    ("k0 0.5 - s", ["--precurvature", "0.5", "--precurvature-slope=-1"], lambda s: 1,
     lambda s: 0.5 - s, 0, 0.75, 0.0, [0.05, 0.15, 0.3]),
    ("compliance 1", ["--support-compliance", "1"], lambda s: 1, lambda s: 0, 1, 0.75, 0.0,
     [0.05, 0.15, 0.3]),
    ("surface +0.3", ["--surface-angle", "0.3"], lambda s: 1, lambda s: 0, 0, 0.75, 0.3,
     [0.02, 0.06, 0.1]),
    ("surface -0.3", ["--surface-angle=-0.3"], lambda s: 1, lambda s: 0, 0, 0.75, -0.3,
     [0.05, 0.3, 0.8]),
]
TAPERS = {"taper 0.7": "0.7", "taper 0.3 eta 0.9": "0.3", "taper 0.1 eta 0.97": "0.1"}


def preset(file, ds):
    """A scene of data/scenes (taper and linear rest curvature, clamped, flat surface)."""
    import tomllib
    with open(f"data/scenes/{file}", "rb") as fh:
        sc = tomllib.load(fh)
    rho = sc["stiffness"]["ratio"]
    k0, k1 = sc["precurvature"]["k0"], sc["precurvature"].get("k1", 0.0)
    assert sc.get("support_compliance", 0.0) == 0.0 and sc.get("surface_angle", 0.0) == 0.0
    return (file, ["--scene", f"data/scenes/{file}"], taper(rho), lambda s: k0 + k1 * s, 0.0,
            sc["eta"], 0.0, ds)
LIFT_OFF = ("lift-off k0 -1 c 0.5 eta 0.8",
            ["--precurvature=-1", "--support-compliance", "0.5", "--eta", "0.8"],
            lambda s: 1, lambda s: -1, 0.5, 0.8, 0.0)


def taper(rho):
    return lambda s: (1 - (1 - rho) * s) ** -4


SCENES += [
    preset("rat_mystacial_long.toml", [0.01, 0.02, 0.035]),
    preset("rat_mystacial_short.toml", [0.01, 0.025, 0.04]),
]


def shoot(b, k0, c, m0, f, alpha, rtol=None):
    """z(1) for the foot state given by (m0, f, alpha)."""
    rtol = rtol or RTOL
    F = lambda s, z: [cos(z[2]), sin(z[2]), k0(s) + b(s) * z[3], f * cos(z[2] - alpha)]
    sol = solve_ivp(F, (0.0, 1.0), [0.0, 0.0, pi / 2 + c * m0, m0], method="DOP853",
                    rtol=rtol, atol=1e-2 * rtol)
    assert sol.success, sol.message
    return sol.y[:, -1]


def solve(res, guess):
    r = root(lambda v: res(*v), guess, method="hybr", options={"xtol": 1e-15})
    v = r.x
    assert max(abs(np.asarray(res(*v)))) < 1e-12, (r.message, res(*v))
    return v


def program(flags, d_max, points):
    """The program's scan (rows as dicts): the starting guesses."""
    out = subprocess.run([BIN, "scan", *flags, "--d-max", str(d_max), "--points", str(points),
                          "--tol", "1e-12"], capture_output=True, text=True, check=True).stdout
    return list(csv.DictReader(out.splitlines()))


def solve_start(b, k0, c, eta, beta, guess):
    res = lambda m0, f: (lambda z: [z[3], z[1] - eta])(shoot(b, k0, c, m0, f, beta))
    m0, f = solve(res, guess)
    return shoot(b, k0, c, m0, f, beta)[0]


def solve_point(b, k0, c, eta, xstar, d, guess, rtol=None):
    def res(m0, f, alpha):
        z = shoot(b, k0, c, m0, f, alpha, rtol)
        return [z[3], z[0] - (xstar - d), z[1] - eta]
    return solve(res, guess)


def main():
    rows = []
    spread = 0.0
    for name, flags, b, k0, c, eta, beta, ds in SCENES:
        if b is None:
            b = taper(float(TAPERS[name]))
        start = program(flags, max(ds) + 0.01, 2)[0]
        xstar = solve_start(b, k0, c, eta, beta, [float(start["m_base"]), float(start["f"])])
        for d in ds:
            p = program(flags, d, 2)[-1]
            assert p["event"] == "" and abs(float(p["d"]) - d) < 1e-15, (name, p)
            guess = [float(p["m_base"]), float(p["f"]), float(p["alpha"])]
            m0, f, alpha = solve_point(b, k0, c, eta, xstar, d, guess)
            # the same at 10x the integrator tolerance: the reference's own accuracy
            loose = solve_point(b, k0, c, eta, xstar, d, guess, 10 * RTOL)
            spread = max(spread, abs(np.tan(beta - loose[2]) - np.tan(beta - alpha)))
            rows.append([name, "point", repr(d), repr(float(np.tan(beta - alpha))),
                         repr(float(f)), repr(float(alpha)), repr(float(m0))])
            print(rows[-1], file=sys.stderr)
    name, flags, b, k0, c, eta, beta = LIFT_OFF
    start = program(flags, 0.5, 2)[0]
    xstar = solve_start(b, k0, c, eta, beta, [float(start["m_base"]), float(start["f"])])
    ev = program(flags, 1.115, 224)[-1]
    assert ev["event"] == "lift_off", ev
    alpha = beta - pi / 2
    res = lambda m0, f: (lambda z: [z[3], z[1] - eta])(shoot(b, k0, c, m0, f, alpha))
    m0, f = solve(res, [float(ev["m_base"]), float(ev["f"])])
    d = xstar - shoot(b, k0, c, m0, f, alpha)[0]
    rows.append([name, "lift_off", repr(float(d)), "inf", repr(float(f)), repr(float(alpha)),
                 repr(float(m0))])
    print(rows[-1], file=sys.stderr)
    print(f"largest change of mu at 10x the integrator tolerance: {spread:.2e}", file=sys.stderr)
    with open("data/vibrissa/reference.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["scene", "kind", "d", "mu", "f", "alpha", "m_base"])
        w.writerows(rows)


if __name__ == "__main__":
    main()
