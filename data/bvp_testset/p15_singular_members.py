"""Problem 15 of the Cash-Mazzia set, eps y'' = x y, y(-1) = y(1) = 1, is singular where the
homogeneous problem (y(-1) = y(1) = 0) has a nonzero solution: y'' = (x/eps) y oscillates for
x < 0, so such eps accumulate at 0, and continuation in eps from 0.1 must cross them.

Finds those in [0.02, 0.1] as zeros of y(1; eps) for y(-1) = 0, y'(-1) = 1 (scipy solve_ivp,
DOP853, rtol 1e-12; Brent). Run: python3 p15_singular_members.py
"""
import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq


def y_end(eps):
    s = solve_ivp(lambda x, y: [y[1], x * y[0] / eps], [-1, 1], [0.0, 1.0],
                  method="DOP853", rtol=1e-12, atol=1e-14)
    return s.y[0, -1]


grid = np.geomspace(0.1, 0.02, 400)
vals = [y_end(e) for e in grid]
for e0, e1, v0, v1 in zip(grid, grid[1:], vals, vals[1:]):
    if np.sign(v0) != np.sign(v1):
        print(f"singular member: eps = {brentq(y_end, e1, e0, xtol=1e-15):.12f}")
