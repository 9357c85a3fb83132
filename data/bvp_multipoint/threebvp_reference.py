"""Reference solution of the three-point problem of the bvp4c tutorial (Lin & Segel; MATLAB's
threebvp), used by crates/bvp/tests/multipoint.rs:

    v' = (C - 1) / n,   C' = (v C - min(x, 1)) / eta     on [0, lambda], interface at x = 1,
    v(0) = 0,  C(lambda) = 1,  v and C continuous at x = 1,
    n = 5e-2, lambda = 2, kappa = 2, eta = lambda^2 / (n kappa^2).

Independent of the crate: shooting in C(0) with scipy's DOP853 at rtol 1e-13, atol 1e-15,
integrating [0, 1] and [1, lambda] separately (the right-hand side has a corner at x = 1), the
root by Brent's method to 1e-15 (bracketed by the first sign change on a grid of C(0)). Writes threebvp_reference.csv (x, v, C on 2001 equal points of
[0, lambda]) and threebvp_reference.txt (C(0), and the change against rtol 1e-11).

    python3 data/bvp_multipoint/threebvp_reference.py   (scipy; not needed by CI)
"""
import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

N, LAM, KAPPA = 5e-2, 2.0, 2.0
ETA = LAM**2 / (N * KAPPA**2)


def rhs(x, y):
    return [(y[1] - 1.0) / N, (y[0] * y[1] - min(x, 1.0)) / ETA]


def shoot(c0, rtol):
    y = [0.0, c0]
    for lo, hi in [(0.0, 1.0), (1.0, LAM)]:
        r = solve_ivp(rhs, (lo, hi), y, method="DOP853", rtol=rtol, atol=1e-15)
        assert r.success, r.message
        y = list(r.y[:, -1])
    return y


def end_defect(c0, rtol):
    return shoot(c0, rtol)[1] - 1.0


def bracket(rtol):
    """The first sign change of the defect on a grid of C(0) (shots that blow up skipped)."""
    last = None
    for c in np.linspace(0.05, 1.95, 39):
        try:
            d = end_defect(c, rtol)
        except AssertionError:
            last = None
            continue
        if last is not None and np.sign(d) != np.sign(last[1]):
            return last[0], c
        last = (c, d)
    raise RuntimeError("no sign change")


c0 = brentq(lambda c: end_defect(c, 1e-13), *bracket(1e-13), xtol=1e-15, rtol=1e-15)
c0_loose = brentq(lambda c: end_defect(c, 1e-11), *bracket(1e-11), xtol=1e-15, rtol=1e-15)
x = np.linspace(0.0, LAM, 2001)
rows = []
y0 = [0.0, c0]
for lo, hi in [(0.0, 1.0), (1.0, LAM)]:
    sel = (x >= lo) & (x <= hi)
    r = solve_ivp(rhs, (lo, hi), y0, method="DOP853", rtol=1e-13, atol=1e-15, t_eval=x[sel])
    assert r.success
    for t, v, c in zip(r.t, r.y[0], r.y[1]):
        if lo > 0.0 and t == lo:
            continue
        rows.append((t, v, c))
    y0 = list(solve_ivp(rhs, (lo, hi), y0, method="DOP853", rtol=1e-13, atol=1e-15).y[:, -1])
np.savetxt(__file__.replace(".py", ".csv"), np.array(rows), delimiter=",", header="x,v,C",
           comments="", fmt="%.17g")
with open(__file__.replace(".py", ".txt"), "w") as f:
    f.write(f"C(0) = {c0:.17g}\n")
    f.write(f"change of C(0) from rtol 1e-11 to 1e-13: {abs(c0 - c0_loose):.2e}\n")
    f.write(f"C(lambda) - 1 = {end_defect(c0, 1e-13):.2e}\n")
print(open(__file__.replace(".py", ".txt")).read())
