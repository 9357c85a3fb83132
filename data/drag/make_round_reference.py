#!/usr/bin/env python3
"""Independent reference of the drag of a round tip (issue 31): the uniform clamped rod whose end
carries a rigid disk of radius r, on a corrugation whose flanks are steeper than 45 degrees.

Scene (every parameter; see data/drag/README.md):

  rod       uniform, clamped (phi(0) = pi/2), straight, length 1
  surface   h(x) = 0.75 + 0.02 sin(2 pi x / 0.1 + PHASE)   (largest slope 1.2566, 51.5 degrees)
  friction  mu_s = 0.5, mu_k = 0.3 (uniform)
  tip       a disk of radius r = 0.005 centred at the rod's end P = (x(1), y(1)), turning with it

Rod (normalized units, arc length s from the foot; none of the crate's code):

    x' = cos(phi),  y' = sin(phi),  phi' = m,  m' = Fx sin(phi) - Fy cos(phi)
    x(0) = y(0) = 0,  phi(0) = pi/2

integrated by scipy's DOP853 (`solve_ivp`, rtol = atol = RTOL); equations solved by Powell's
hybrid method (`optimize.root`, `hybr`, xtol 1e-15), events by Brent's method (`brentq`, xtol
1e-15). At the surface's lab x: t = atan h'(x), normal into the obstacle n = (-sin t, cos t),
tangent t_ = -(cos t, sin t); arc length sigma(x) from x = 0 by `quad` (1e-14). The disk
touches at C = (xc, h(xc)), P = C - r n(xc). The contact force F = (Fx, Fy) = -N n + T t_ acts at
C: the rod's end carries F and its moment about P, r n x F = r T, so m(1) = r T. mu = T / N.

  start   the rod pressed onto the flat line y = 0.75 (the disk touching it at its top, force
          vertical: m(1) = 0, y(1) = 0.75 - r; unknowns m(0), N), then the corrugation grown in
          20 steps of its amplitude with the force normal to the profile (frictionless: unknowns
          m(0), N, xc; m(1) = 0, P = C - r n)
  stick   the foot at d; unknowns m(0), Fx, Fy, xc: m(1) = r T, P = C - r n(xc) (the end in the
          foot's frame: x(1) = xc + r sin t - d, y(1) = h(xc) - r cos t), and rolling without
          slip, sigma(xc) - sigma(xc0) = r [(phi(1) - t(xc)) - (phi(1)_0 - t(xc0))] (0: where
          it stuck); d marched in steps of 0.002, the slip where |mu| = mu_s bracketed and
          located by brentq
  slip    the foot held at d_s; the contact point moved along the surface in lab xc (steps of
          0.001 in the direction of the slip, dir the sign of mu) with unknowns m(0), Fx, Fy and
          m(1) = r T, P = C - r n(xc), until dir*mu falls to mu_k (brentq); it sticks there
          (the new xc0, phi(1)_0). The material slip of the disk along the surface,
          sigma(xc) - r (phi(1) - t(xc)), is checked to move the way dir says.

Checked at every output and event state: N > 0; the centreline below the surface at every
sampled s (clearance > 0: no side touches down); the disk nowhere closer to the surface than r
except at C (no second contact of the disk).

Checked once (printed): the energy balances of the first stick phase (foot work = change of the
elastic energy: the rolling disk does no work) and of the first slip (energy released = the
integral of T dq, q = sigma(xc) - r (phi(1) - t(xc)) the disk's material slip), which the signs
of m(1) = r T and of the rolling condition must satisfy.

Output `round_tip_reference.csv`: kind, k, d, x_contact, x_tip, mu, slope - `slip` (the state
just before slip k), `slip_end` (just after), `row` (an output displacement d of a stick phase);
x_contact the lab x of C, x_tip the lab x of the disk's centre P, slope h'(x_contact). The
script runs at RTOL = 1e-13 and 1e-12 and prints the largest difference (its own spread).

    pip install scipy; python3 data/drag/make_round_reference.py      (about a minute)

The environment may override the scene for checks and searches (AMPLITUDE, WAVELENGTH, PHASE,
RADIUS, D_MAX, POINTS, SLIPS, RTOLS, OUT); EXPLORE=1 runs one tolerance and reports the first
failed check (how the phase and d_max were chosen).
"""
import csv
import math
import os
import sys

import numpy as np
from scipy.integrate import quad, simpson, solve_ivp
from scipy.optimize import brentq, root

# the scene; the environment overrides it only for checks (README: R = 0 against reference.csv)
ETA = 0.75
A = float(os.environ.get("AMPLITUDE", "0.02"))
LAM = float(os.environ.get("WAVELENGTH", "0.1"))
PHASE = float(os.environ.get("PHASE", "5.0"))
R = float(os.environ.get("RADIUS", "0.005"))
MU_S, MU_K = 0.5, 0.3
D_MAX = float(os.environ.get("D_MAX", "0.02"))
POINTS = int(os.environ.get("POINTS", "21"))
SLIPS = int(os.environ.get("SLIPS", "100"))
K = 2 * math.pi / LAM


def h(x, amp=1.0):
    return ETA + amp * A * math.sin(K * x + PHASE)


def dh(x, amp=1.0):
    return amp * A * K * math.cos(K * x + PHASE)


def th(x, amp=1.0):
    return math.atan(dh(x, amp))


def sigma(x):
    return quad(lambda t: math.sqrt(1 + dh(t) ** 2), 0.0, x, epsabs=1e-14, epsrel=1e-14,
                limit=400)[0]


def solve(fun, guess):
    r = root(fun, guess, method="hybr", options={"xtol": 1e-15})
    res = np.max(np.abs(fun(r.x)))
    if res > 1e-12:
        raise RuntimeError(f"no convergence: residual {res:.3e} at {r.x}")
    return r.x


class Rod:
    def __init__(self, rtol):
        self.rtol = rtol

    def f(self, fx, fy):
        def f(s, z):
            return [math.cos(z[2]), math.sin(z[2]), z[3],
                    fx * math.sin(z[2]) - fy * math.cos(z[2])]
        return f

    def tip(self, m0, fx, fy):
        r = solve_ivp(self.f(fx, fy), (0.0, 1.0), [0.0, 0.0, math.pi / 2, m0], method="DOP853",
                      rtol=self.rtol, atol=self.rtol)
        return r.y[:, -1]

    def dense(self, m0, fx, fy):
        return solve_ivp(self.f(fx, fy), (0.0, 1.0), [0.0, 0.0, math.pi / 2, m0],
                         method="DOP853", rtol=self.rtol, atol=self.rtol, dense_output=True).sol


def nt(fx, fy, t):
    """N and T of the force F on the rod in the frame at surface angle t."""
    return fx * math.sin(t) - fy * math.cos(t), -fx * math.cos(t) - fy * math.sin(t)


class Drag:
    def __init__(self, rod):
        self.rod = rod

    def start(self):
        rod = self.rod

        def flat(v):
            z = rod.tip(v[0], 0.0, -v[1])
            return [z[3], z[1] - (ETA - R)]
        m0, nn = solve(flat, [-1.4, 4.7])
        x = rod.tip(m0, 0.0, -nn)[0]
        v = np.array([m0, nn, x])
        for amp in np.linspace(0.0, 1.0, 21)[1:]:
            def grown(w, amp=amp):
                t = th(w[2], amp)
                z = rod.tip(w[0], -w[1] * -math.sin(t), -w[1] * math.cos(t))
                return [z[3], z[0] - (w[2] + R * math.sin(t)), z[1] - (h(w[2], amp) - R * math.cos(t))]
            v = solve(grown, v)
        t = th(v[2])
        return v[2], np.array([v[0], v[1] * math.sin(t), -v[1] * math.cos(t)])

    def place(self, xc, d, z):
        """Residuals of the disk touching at xc with the rod's end z (foot at d)."""
        t = th(xc)
        return [z[0] + d - (xc + R * math.sin(t)), z[1] - (h(xc) - R * math.cos(t))]

    def stuck(self, anchor, d, guess):
        """anchor = (xc0, sigma(xc0), psi0); unknowns m0, Fx, Fy, xc."""
        xc0, sg0, psi0 = anchor

        def fun(v):
            z = self.rod.tip(*v[:3])
            t = th(v[3])
            _, tt = nt(v[1], v[2], t)
            return [z[3] - R * tt, *self.place(v[3], d, z),
                    sigma(v[3]) - sg0 - R * ((z[2] - t) - psi0)]
        u = solve(fun, guess)
        return u, self.mu(u[:3], u[3])

    def held(self, xc, d, guess):
        """The slide at the held foot: unknowns m0, Fx, Fy with the contact at xc."""
        def fun(v):
            z = self.rod.tip(*v)
            _, tt = nt(v[1], v[2], th(xc))
            return [z[3] - R * tt, *self.place(xc, d, z)]
        u = solve(fun, guess)
        return u, self.mu(u, xc)

    def mu(self, u, xc):
        nn, tt = nt(u[1], u[2], th(xc))
        if nn <= 0:
            raise RuntimeError(f"lift-off: N = {nn}")
        return tt / nn

    def anchor(self, u, xc):
        z = self.rod.tip(*u[:3])
        return (xc, sigma(xc), z[2] - th(xc))

    def check(self, u, xc, d):
        """No side touches down; the disk touches the surface only at C."""
        sol = self.rod.dense(*u[:3])
        ss = np.linspace(0.0, 1.0, 2001)[:-1]
        zs = sol(ss)
        gaps = [h(zs[0, i] + d) - zs[1, i] for i in range(len(ss))]
        gap = min(gaps)
        assert gap > 0, (f"the centreline crosses the surface at d = {d}, "
                         f"s = {ss[int(np.argmin(gaps))]}: {gap}")
        pe = sol(1.0)
        px, py = pe[0] + d, pe[1]
        dist = min(math.hypot(x - px, h(x) - py) for x in np.linspace(px - 0.05, px + 0.05, 4001)
                   if abs(x - xc) > 2e-3)
        assert dist > R, f"the disk touches a second time at d = {d}: {dist}"
        return gap, dist

    def run(self, grid):
        out = []
        self.slips_seen, self.slopes = [], []
        xc, f = self.start()
        u = np.array([*f, xc])
        anchor = self.anchor(u, xc)
        d, k, slope_max, gap_min = 0.0, 0, 0.0, 1.0

        def record(kind, dd, uu, xcc, m):
            nonlocal slope_max, gap_min
            g, _ = self.check(uu, xcc, dd)
            gap_min = min(gap_min, g)
            slope_max = max(slope_max, abs(dh(xcc)))
            self.slopes.append(round(dh(xcc), 3))
            z = self.rod.tip(*uu[:3])
            out.append((kind, k, dd, xcc, z[0] + dd, m, dh(xcc)))
        while k < SLIPS:
            cache = {d: u}

            def g(dd):
                best = min(cache, key=lambda c: abs(c - dd))
                uu, m = self.stuck(anchor, dd, cache[best])
                cache[dd] = uu
                return abs(m) - MU_S
            dp, ds = d, None
            while ds is None and dp < D_MAX:
                dn = min(dp + 0.002, D_MAX)
                if g(dn) > 0:
                    ds = brentq(g, dp, dn, xtol=1e-15, rtol=1e-15)
                dp = dn
            for gd in grid:
                if (d < gd or (k == 0 and gd == 0.0)) and (ds is None or gd < ds):
                    g(gd)
                    uu = cache[gd]
                    record("row", gd, uu, uu[3], self.mu(uu[:3], uu[3]))
            if ds is None:
                break
            g(ds)
            u = cache[ds]
            xa = u[3]
            mu0 = self.mu(u[:3], xa)
            record("slip", ds, u, xa, mu0)
            self.slips_seen.append(ds)
            side = 1.0 if mu0 > 0 else -1.0
            cache2 = {xa: u[:3]}

            def need(xx):
                best = min(cache2, key=lambda c: abs(c - xx))
                uu, m = self.held(xx, ds, cache2[best])
                cache2[xx] = uu
                return side * m
            x, stop = xa, None
            q_prev = sigma(xa) - R * anchor[2]
            while stop is None:
                xn = x + side * 0.001
                if need(xn) - MU_K <= 0:
                    stop = brentq(lambda xx: need(xx) - MU_K, x, xn, xtol=1e-15, rtol=1e-15)
                    need(stop)
                else:
                    x = xn
                # the disk's material point slips the way the friction opposes
                xs = stop if stop is not None else x
                q = sigma(xs) - R * (self.rod.tip(*cache2[xs])[2] - th(xs))
                assert side * (q - q_prev) > 0, "the slip runs against its friction"
                q_prev = q
            need(stop)
            u = np.array([*cache2[stop], stop])
            record("slip_end", ds, u, stop, self.mu(u[:3], stop))
            anchor = self.anchor(u, stop)
            d, k = ds, k + 1
        print(f"phase {PHASE}: {k} slips up to d = {D_MAX}; steepest slope at the contact "
              f"{slope_max:.4f} ({math.degrees(math.atan(slope_max)):.1f} deg); smallest "
              f"clearance of the centreline {gap_min:.3e}", file=sys.stderr)
        return out


def energy_check(rtol, rows):
    """Energy balances, a check of m(1) = r T and of the rolling condition's sign: over the first
    stick phase the foot's work, the integral of -Fx dd, equals the change of the elastic
    energy E, the integral of m^2 / 2 ds (a disk rolling without slip does no work); over the
    first slip the energy released equals the integral of T dq, q = sigma(xc) - r (phi(1) -
    t(xc)) the disk's material slip along the surface."""
    dr = Drag(Rod(rtol))
    xc, f = dr.start()
    u = np.array([*f, xc])
    anchor = dr.anchor(u, xc)

    def energy(u):
        def g(s, z):
            return [math.cos(z[2]), math.sin(z[2]), z[3],
                    u[1] * math.sin(z[2]) - u[2] * math.cos(z[2]), 0.5 * z[3] ** 2]
        return solve_ivp(g, (0.0, 1.0), [0.0, 0.0, math.pi / 2, u[0], 0.0], method="DOP853",
                         rtol=rtol, atol=rtol).y[4, -1]
    slip = next(r for r in rows if r[0] == "slip")
    end = next(r for r in rows if r[0] == "slip_end")
    ds = np.linspace(0.0, slip[2], 41)
    es, fxs = [], []
    for d in ds:
        u, _ = dr.stuck(anchor, d, u)
        es.append(energy(u))
        fxs.append(u[1])
    work = simpson(-np.array(fxs), x=ds)
    v = u[:3]
    xs = np.linspace(slip[3], end[3], 81)
    el, ts, qs = [], [], []
    for x in xs:
        v, _ = dr.held(x, slip[2], v)
        el.append(energy(v))
        ts.append(nt(v[1], v[2], th(x))[1])
        qs.append(sigma(x) - R * (dr.rod.tip(*v)[2] - th(x)))
    diss = simpson(ts, x=qs)
    print(f"energy balance of the first stick: foot work {work:.12e}, energy change "
          f"{es[-1] - es[0]:.12e}, difference {work - (es[-1] - es[0]):.1e}; of the first slip: "
          f"released {el[0] - el[-1]:.12e}, int T dq {diss:.12e}, difference "
          f"{el[0] - el[-1] - diss:.1e}", file=sys.stderr)


def main():
    grid = [D_MAX * i / (POINTS - 1) for i in range(POINTS)]
    tols = [float(t) for t in os.environ.get("RTOLS", "1e-13,1e-12").split(",")]
    if os.environ.get("EXPLORE"):
        dr = Drag(Rod(tols[0]))
        try:
            dr.run(grid)
        except (AssertionError, RuntimeError) as e:
            print(f"phase {PHASE}: stopped after {len(dr.slips_seen)} slips "
                  f"{['%.4f' % v for v in dr.slips_seen]}, slopes {dr.slopes}: {e}", file=sys.stderr)
        return
    runs = [Drag(Rod(rtol)).run(grid) for rtol in tols]
    energy_check(tols[0], runs[0])
    if len(runs) == 2:
        a, b = runs
        assert [r[:2] for r in a] == [r[:2] for r in b]
        spread = max(abs(p[i] - q[i]) for p, q in zip(a, b) for i in (2, 3, 4, 5))
        print(f"largest change from rtol {tols[0]} to {tols[1]} (d, x_contact, x_tip, mu): "
              f"{spread:.3e}", file=sys.stderr)
    with open(os.environ.get("OUT", "data/drag/round_tip_reference.csv"), "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["kind", "k", "d", "x_contact", "x_tip", "mu", "slope"])
        for kind, k, d, xc, xt, mu, sl in runs[0]:
            w.writerow([kind, k] + [repr(float(v)) for v in (d, xc, xt, mu, sl)])


if __name__ == "__main__":
    main()
