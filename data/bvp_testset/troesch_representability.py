"""Problem 23 of the Cash-Mazzia set (Troesch): y'' = mu sinh(mu y), y(0) = 0, y(1) = 1, mu = 1/eps.

How large the exact solution and the equation get at x = 1, and where the layer lies against the
doubles next to 1, in 40-digit arithmetic (mpmath). First integral: y'^2 = s^2 + 2 (cosh(mu y) - 1)
with s = y'(0), so the distance of the point where y = v from x = 1 is

    1 - x(v) = int_v^1 d eta / sqrt(s^2 + 2 cosh(mu eta) - 2),

and s solves 1 - x(0) = 1. Near x = 1 the solution follows y = -(2/mu) ln(mu (c - x) / 2), a
logarithmic pole at c = 1 + (2/mu) e^{-mu/2} beyond the end. Run: python3 troesch_representability.py
"""
import mpmath as mp

mp.mp.dps = 40
LAST = mp.mpf(2) ** -53  # 1 - (largest double below 1)


def dist(v, s, mu):
    """1 - x(v): the distance from x = 1 of the point where y = v."""
    # 2 (cosh t - 1) = 4 sinh^2(t/2), without cancellation for tiny t.
    f = lambda e: 1 / mp.sqrt(s**2 + 4 * mp.sinh(mu * e / 2) ** 2)
    # Breakpoints: geometric from the integrand's inner scale s/mu near 0, then uniform.
    geo = [s / mu * mp.mpf(10) ** k for k in range(-2, 60)] if s > 0 else []
    pts = [v] + sorted(p for p in geo + [mp.mpf(k) / 80 for k in range(81)] if v < p < 1) + [mp.mpf(1)]
    return mp.quad(f, pts)


def layer(mu):
    mu = mp.mpf(mu)
    # s = y'(0) from 1 - x(0) = 1 in ln s (start from the asymptote 8 e^{-mu}).
    # 1 - x(0) decreases in s: bisection in ln s around the asymptote ln 8 - mu.
    lo, hi = mp.log(8) - mu - 5, mp.log(8) - mu + 5
    for _ in range(60):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if dist(mp.mpf(0), mp.e**mid, mu) > 1 else (lo, mid)
    s = mp.e ** ((lo + hi) / 2)
    resid = dist(mp.mpf(0), s, mu) - 1
    # y at the largest double below 1 (dist decreases in v: bisection).
    lo, hi = mp.mpf(0), mp.mpf(1)
    for _ in range(70):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if dist(mid, s, mu) > LAST else (lo, mid)
    return s, resid, dist(mp.mpf("0.5"), s, mu), lo


def sizes(mu):
    mu = mp.mpf(mu)
    return (mp.sqrt(2 * (mp.cosh(mu) - 1)), mu * mp.sinh(mu), mu**2 * mp.cosh(mu), 2 / mu * mp.e ** (-mu / 2))


print("DBL_MAX = 1.797e308; 1 - (largest double below 1) = 2^-53 = 1.11e-16")
print("eps | y'(1) | y''(1) = mu sinh mu | dphi/dy(1) = mu^2 cosh mu | pole c - 1 | y'(0) | 1 - x(y = 0.5) | y(1 - 2^-53)")
for eps in ["0.1", "0.04", "0.02", "0.01", "0.001", "0.0001"]:
    mu = 1 / mp.mpf(eps)
    yp1, ypp1, jac, pole = sizes(mu)
    row = [eps] + [mp.nstr(v, 4) for v in (yp1, ypp1, jac, pole)]
    if mu <= 100:
        s, resid, half, ylast = layer(mu)
        assert abs(resid) < mp.mpf(10) ** -12, resid
        row += [mp.nstr(s, 8), mp.nstr(half, 4), mp.nstr(ylast, 6)]
    else:
        row += ["-", "-", "-"]
    print(" | ".join(row))
