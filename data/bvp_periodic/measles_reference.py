"""Reference solution of the seasonal epidemic problem with periodic conditions (Schwartz 1983;
the "measles" example of the bvp4c tutorial by Shampine, Kierzenka & Reichelt), used by
crates/bvp/tests/periodic.rs:

    y1' = mu - beta(t) y1 y3
    y2' = beta(t) y1 y3 - y2 / lam
    y3' = y2 / lam - y3 / eta,        beta(t) = beta0 (1 + cos 2 pi t),
    y(0) = y(1),   mu = 0.02, lam = 0.0279, eta = 0.01, beta0 = 1575.

Independent of the crate: scipy's DOP853 at rtol 1e-12, atol 1e-16 from the periodic initial
state, found by Newton on y(1; y0) - y0 = 0 with the monodromy matrix from the variational
equations (same integrator). Writes measles_reference.csv: t, y1, y2, y3 on 2001 equal points of
[0, 1], and the periodicity defect and the change of y(0) between rtol 1e-10 and 1e-12 (the
reference's accuracy) in measles_reference.txt.

    python3 data/bvp_periodic/measles_reference.py   (scipy; not needed by CI)
"""
import numpy as np
from scipy.integrate import solve_ivp

MU, LAM, ETA, BETA0 = 0.02, 0.0279, 0.01, 1575.0


def beta(t):
    return BETA0 * (1.0 + np.cos(2.0 * np.pi * t))


def rhs(t, y):
    b = beta(t)
    return [MU - b * y[0] * y[2], b * y[0] * y[2] - y[1] / LAM, y[1] / LAM - y[2] / ETA]


def jac(t, y):
    b = beta(t)
    return np.array([
        [-b * y[2], 0.0, -b * y[0]],
        [b * y[2], -1.0 / LAM, b * y[0]],
        [0.0, 1.0 / LAM, -1.0 / ETA],
    ])


def variational(t, w):
    y, phi = w[:3], w[3:].reshape(3, 3)
    return np.concatenate([rhs(t, y), (jac(t, y) @ phi).ravel()])


def flow(y0, rtol, t_eval=None):
    w0 = np.concatenate([y0, np.eye(3).ravel()])
    r = solve_ivp(variational, (0.0, 1.0), w0, method="DOP853", rtol=rtol, atol=1e-16,
                  t_eval=t_eval, dense_output=False)
    assert r.success, r.message
    return r


def periodic_state(rtol, y0):
    for _ in range(20):
        r = flow(y0, rtol)
        y1, phi = r.y[:3, -1], r.y[3:, -1].reshape(3, 3)
        d = np.linalg.solve(phi - np.eye(3), -(y1 - y0))
        lam = 1.0
        while np.any(y0 + lam * d <= 0.0):
            lam /= 2.0
        y0 = y0 + lam * d
        print(f"rtol {rtol:g}: correction {np.max(np.abs(d) / np.abs(y0)):.1e}", flush=True)
        if np.max(np.abs(d) / np.abs(y0)) < 1e-13:
            break
    return y0


# A start near the periodic orbit (3 digits; Newton from a crude one wanders).
y0 = periodic_state(1e-12, np.array([0.075, 1.8e-5, 5e-6]))
y0_loose = periodic_state(1e-10, y0)
t = np.linspace(0.0, 1.0, 2001)
r = solve_ivp(rhs, (0.0, 1.0), y0, method="DOP853", rtol=1e-12, atol=1e-16, t_eval=t)
defect = np.max(np.abs(r.y[:3, -1] - y0) / np.abs(y0))
change = np.max(np.abs(y0 - y0_loose) / np.abs(y0))
np.savetxt(__file__.replace(".py", ".csv"), np.column_stack([t, r.y[:3].T]), delimiter=",",
           header="t,y1,y2,y3", comments="", fmt="%.17g")
with open(__file__.replace(".py", ".txt"), "w") as f:
    f.write(f"y(0) = {y0[0]:.17g} {y0[1]:.17g} {y0[2]:.17g}\n")
    f.write(f"relative periodicity defect of the reference: {defect:.2e}\n")
    f.write(f"relative change of y(0) from rtol 1e-10 to 1e-12: {change:.2e}\n")
print(open(__file__.replace(".py", ".txt")).read())
