#!/usr/bin/env python3
"""scipy.integrate.solve_bvp on scipy's own large test problems (test_big_problem and
test_big_problem_with_parameters of scipy/integrate/tests/test_bvp.py), for 2*pairs states:
same functions, meshes (5 nodes), guesses, tol (1e-3) and no Jacobians (scipy's tests pass
none), as crates/bvp/benches/large.rs runs them (bvp::samples::Big). Prints one line per case:
`name seconds` (minimum over repeats for at least 1 s), which the bench reads.

    python3 data/bvp_large/scipy_big.py 5 10 20 30
"""
import sys
import time

import numpy as np
from scipy.integrate import solve_bvp


def big_fun(x, y):
    f = np.zeros_like(y)
    f[::2] = y[1::2]
    return f


def big_bc(ya, yb):
    return np.hstack((ya[::2], yb[::2] - 1))


def big_fun_p(x, y, p):
    f = np.zeros_like(y)
    f[::2] = y[1::2]
    f[1::4] = -p[0] ** 2 * y[::4]
    f[3::4] = -p[1] ** 2 * y[2::4]
    return f


def big_bc_p(ya, yb, p):
    return np.hstack((ya[::2], yb[::2], ya[1] - p[0], ya[3] - p[1]))


def timed(f):
    best, total = float("inf"), 0.0
    while total < 1.0:
        t = time.perf_counter()
        sol = f()
        dt = time.perf_counter() - t
        best, total = min(best, dt), total + dt
        assert sol.status == 0, sol.message
    return best


def main():
    for pairs in [int(a) for a in sys.argv[1:]] or [30]:
        n = 2 * pairs
        x = np.linspace(0, 1, 5)
        t = timed(lambda: solve_bvp(big_fun, big_bc, x, np.zeros((n, x.size))))
        print(f"big/{n} {t:.6e}")
        x = np.linspace(0, np.pi, 5)
        t = timed(lambda: solve_bvp(big_fun_p, big_bc_p, x, np.ones((n, x.size)), p=[0.5, 0.5]))
        print(f"big_params/{n} {t:.6e}")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
