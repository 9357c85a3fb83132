#!/usr/bin/env python3
"""Independent reference of the drag (issue 21) for crate `vibrissa` (tests/drag.rs).

Two scenes of the uniform clamped rod (tip contact only):

  corrugated   h(x) = 0.75 + 0.01 sin(2 pi x / 0.2 + 2.0),  mu_s = 0.5, mu_k = 0.3
  two patches  h(x) = 0.75; period 0.1: [0, 0.05) mu_s 0.4, mu_k 0.3; [0.05, 0.1) mu_s 0.7,
               mu_k 0.5 (a point on a patch edge belongs to the patch ahead of a slip)

Rod (normalized units, arc length s from the foot, none of the crate's code):

    x' = cos(phi),  y' = sin(phi),  phi' = m,  m' = Fx sin(phi) - Fy cos(phi)
    x(0) = y(0) = 0,  phi(0) = pi/2,  m(1) = 0

integrated by scipy's DOP853 (`solve_ivp`, rtol = atol = RTOL); equations solved by Powell's
hybrid method (`optimize.root`, `hybr`, xtol 1e-15), events by Brent's method (`brentq`,
xtol 1e-15). F = (Fx, Fy) is the contact force on the rod's tip; on the surface at lab x the
local normal into the obstacle is n = (-sin t, cos t), the tangent t_ = -(cos t, sin t),
t = atan h'(x); N = -F.n, T = F.t_, mu = T / N.

  start   the rod pressed onto the flat line y = 0.75 with a vertical force (unknowns m(0), N),
          then the corrugation grown in 20 steps of its amplitude, the force normal to the
          profile (unknowns m(0), N, X: the tip at (X, h(X)))
  stick   the foot at d, the tip at lab X_a: x(1) = X_a - d, y(1) = h(X_a) (unknowns m(0),
          Fx, Fy); d marched in steps of 0.002, the slip where mu = mu_s(X_a) bracketed and
          located by brentq
  slip    the foot held at d_s, the tip moved along the profile in lab x (the crate moves it in
          arc length): X marched in steps of 0.001 from X_a in the direction of the slip until
          dir*mu falls to mu_k(X) (brentq), or, on a patch edge, until the patch ahead holds it

The seed of the very first solve (the pressed flat rod) is m(0) = -1.4, N = 4.7 (a guess near
the convex pressed rod); everything else follows by continuation. Every solve is checked to a
residual below 1e-12.

Output `reference.csv`: scene, kind, k, d, x_tip, mu — `slip` (the state just before slip k),
`slip_end` (just after), `row` (mu at the output displacement d of a stick phase). The script
runs every scene at RTOL = 1e-13 and 1e-12 and prints the largest difference (its own spread).

    pip install scipy; python3 data/drag/make_reference.py      (a few minutes)
"""
import csv
import math
import sys

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, root


class Sine:
    def __init__(self, eta, a, lam, ph):
        self.eta, self.a, self.k, self.ph = eta, a, 2 * math.pi / lam, ph

    def h(self, x, amp=1.0):
        return self.eta + amp * self.a * math.sin(self.k * x + self.ph)

    def dh(self, x, amp=1.0):
        return amp * self.a * self.k * math.cos(self.k * x + self.ph)


class Flat:
    def __init__(self, eta):
        self.eta = eta

    def h(self, x, amp=1.0):
        return self.eta

    def dh(self, x, amp=1.0):
        return 0.0


class Uniform:
    def __init__(self, mu_s, mu_k):
        self.mu = (mu_s, mu_k)

    def at(self, x, side):
        return self.mu

    def next_edge(self, x, side):
        return None


class Patches:
    def __init__(self, period, starts, mu_s, mu_k):
        self.period, self.starts, self.mu_s, self.mu_k = period, starts, mu_s, mu_k

    def at(self, x, side):
        r = (x + side * 1e-9) % self.period
        i = max(j for j, b in enumerate(self.starts) if b <= r)
        return self.mu_s[i], self.mu_k[i]

    def next_edge(self, x, side):
        n = math.floor(x / self.period)
        edges = [(n + k) * self.period + b for k in (-1, 0, 1, 2) for b in self.starts]
        ahead = [e for e in edges if side * (e - x) > 1e-12]
        return min(ahead, key=lambda e: side * (e - x))


class Rod:
    def __init__(self, rtol):
        self.rtol = rtol

    def tip(self, m0, fx, fy):
        def f(s, z):
            return [math.cos(z[2]), math.sin(z[2]), z[3],
                    fx * math.sin(z[2]) - fy * math.cos(z[2])]
        r = solve_ivp(f, (0.0, 1.0), [0.0, 0.0, math.pi / 2, m0], method="DOP853",
                      rtol=self.rtol, atol=self.rtol)
        return r.y[:, -1]


def solve(fun, guess):
    r = root(fun, guess, method="hybr", options={"xtol": 1e-15})
    res = np.max(np.abs(fun(r.x)))
    if res > 1e-12:
        raise RuntimeError(f"no convergence: residual {res:.3e} at {r.x}")
    return r.x


def frame(prof, x, amp=1.0):
    t = math.atan(prof.dh(x, amp))
    return (-math.sin(t), math.cos(t)), (-math.cos(t), -math.sin(t))


def mu_of(prof, x, fx, fy):
    n, t = frame(prof, x)
    nn = -(fx * n[0] + fy * n[1])
    return (fx * t[0] + fy * t[1]) / nn


class Drag:
    def __init__(self, rod, prof, fric):
        self.rod, self.prof, self.fric = rod, prof, fric

    def start(self):
        rod, prof = self.rod, self.prof
        eta = prof.eta

        def flat(v):
            z = rod.tip(v[0], 0.0, -v[1])
            return [z[3], z[1] - eta]
        m0, nn = solve(flat, [-1.4, 4.7])
        x = rod.tip(m0, 0.0, -nn)[0]
        v = np.array([m0, nn, x])
        for amp in np.linspace(0.0, 1.0, 21)[1:]:
            def grown(w, amp=amp):
                n, _ = frame(prof, w[2], amp)
                z = rod.tip(w[0], -w[1] * n[0], -w[1] * n[1])
                return [z[3], z[0] - w[2], z[1] - prof.h(w[2], amp)]
            v = solve(grown, v)
        n, _ = frame(prof, v[2])
        return v[2], np.array([v[0], -v[1] * n[0], -v[1] * n[1]])

    def stuck(self, xa, d, guess):
        prof, rod = self.prof, self.rod

        def fun(v):
            z = rod.tip(*v)
            return [z[3], z[0] - (xa - d), z[1] - prof.h(xa)]
        u = solve(fun, guess)
        return u, mu_of(prof, xa, u[1], u[2])

    def run(self, d_max, grid, slips_max):
        out = []
        xa, u = self.start()
        d, k = 0.0, 0
        mu_s = self.fric.at(xa, 1.0)[0]
        while k < slips_max:
            # stick: march d, then brentq on mu - mu_s
            u, mu = self.stuck(xa, d, u)
            d_prev, u_prev = d, u
            cache = {}
            def g(dd):
                best = min(cache, key=lambda c: abs(c - dd)) if cache else d_prev
                uu, m = self.stuck(xa, dd, cache.get(best, u_prev))
                cache[dd] = uu
                return m - mu_s
            while True:
                dn = d_prev + 0.002
                if g(dn) > 0:
                    break
                d_prev = dn
                if dn > d_max:
                    break
            if dn > d_max and g(dn) <= 0:
                for gd in grid:
                    if d <= gd <= d_max:
                        out.append(("row", k, gd, xa, g(gd) + mu_s))
                return out
            ds = brentq(g, d_prev, dn, xtol=1e-15, rtol=1e-15)
            for gd in grid:
                if (d < gd or (k == 0 and gd == 0.0)) and gd < ds:
                    out.append(("row", k, gd, xa, g(gd) + mu_s))
            g(ds)
            u = cache[ds]
            out.append(("slip", k, ds, xa, mu_of(self.prof, xa, u[1], u[2])))
            # slip: the tip moved along the profile at the held foot
            mu0 = mu_of(self.prof, xa, u[1], u[2])
            side = 1.0 if mu0 > 0 else -1.0
            x, ux = xa, u
            cache2 = {x: ux}
            def need(xx):
                best = min(cache2, key=lambda c: abs(c - xx))
                uu, m = self.stuck(xx, ds, cache2[best])
                cache2[xx] = uu
                return side * m
            stop = None
            while stop is None:
                edge = self.fric.next_edge(x, side)
                mu_k = self.fric.at(x, side)[1]
                xn = x + side * 0.001
                if edge is not None and side * (xn - edge) >= 0:
                    xn = edge
                if need(xn) - mu_k <= 0:
                    stop = brentq(lambda xx: need(xx) - mu_k, x, xn, xtol=1e-15, rtol=1e-15)
                    mu_s = self.fric.at(stop, side)[0]
                elif edge is not None and xn == edge and need(edge) <= self.fric.at(edge, side)[1]:
                    stop = edge
                    mu_s = self.fric.at(edge, side)[0]
                else:
                    x = xn
            xa = stop
            need(xa)
            u = cache2[xa]
            out.append(("slip_end", k, ds, xa, mu_of(self.prof, xa, u[1], u[2])))
            d, k = ds, k + 1
        return out


SCENES = [
    ("corrugated", lambda: Sine(0.75, 0.01, 0.2, 2.0), lambda: Uniform(0.5, 0.3), 0.12, 13, 4),
    ("two patches", lambda: Flat(0.75),
     lambda: Patches(0.1, [0.0, 0.05], [0.4, 0.7], [0.3, 0.5]), 0.16, 17, 5),
]


def main():
    rows = []
    spread = 0.0
    for name, prof, fric, d_max, points, slips in SCENES:
        grid = [d_max * i / (points - 1) for i in range(points)]
        runs = [Drag(Rod(rtol), prof(), fric()).run(d_max, grid, slips) for rtol in (1e-13, 1e-12)]
        a, b = runs
        assert len(a) == len(b), (name, len(a), len(b))
        for p, q in zip(a, b):
            assert p[:2] == q[:2]
            spread = max(spread, abs(p[2] - q[2]), abs(p[3] - q[3]), abs(p[4] - q[4]))
        for kind, k, d, x, mu in a:
            rows.append((name, kind, k, repr(float(d)), repr(float(x)), repr(float(mu))))
        print(f"{name}: {sum(1 for r in a if r[0] == 'slip')} slips", file=sys.stderr)
    with open("data/drag/reference.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["scene", "kind", "k", "d", "x_tip", "mu"])
        w.writerows(rows)
    print(f"largest change from rtol 1e-13 to 1e-12 (d, x_tip, mu): {spread:.3e}", file=sys.stderr)


if __name__ == "__main__":
    main()
