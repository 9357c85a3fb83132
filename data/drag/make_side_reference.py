#!/usr/bin/env python3
"""Independent reference of a side contact that slides while the tip sticks (issue 31), for
crate `vibrissa` (tests/drag.rs, `a_sliding_side_matches_the_independent_reference`).

Scene: the uniform clamped rod, surface h(x) = 0.75 + 0.02 sin(2 pi x / 0.2 + 4.0), uniform
friction mu_s = 0.5, mu_k = 0.3 (crate: `drag --mu-s 0.5 --mu-k 0.3 --corrugation-amplitude
0.02 --corrugation-wavelength 0.2 --corrugation-phase 4`). The tip sticks from d = 0 on; near
d = 0.154 the rod's side touches down 0.116 behind the tip. Held at its lab point, the tip
would trap the segment between them, so the side slides from the moment it forms with kinetic
friction (a passive slider, T = +-mu_k N), until its slip rate falls to zero (it halts) and
rolls on (no slip) until it needs mu_s itself, near d = 0.273. The tip sticks throughout.

Rod (normalized units, arc length s from the foot; none of the crate's code):

    x' = cos(phi),  y' = sin(phi),  phi' = m,  m' = Fx sin(phi) - Fy cos(phi)
    x(0) = y(0) = 0,  phi(0) = pi/2,  m(1) = 0

(F the force the rod carries beyond s: the sum of the contact forces on the rod beyond s),
integrated by scipy's DOP853 (`solve_ivp`, rtol = atol = RTOL). On the surface at lab x: normal
into the obstacle n = (-sin t, cos t), tangent t_ = -(cos t, sin t), t = atan h'(x); a contact
force on the rod is F = -N n + T t_ (T > 0: towards -x), arc length sigma(x) by `quad`.

  tip only   unknowns m(0), Fx, Fy (the tip force): m(1) = 0, the tip at its lab point
             (X_a - d, h(X_a)) in the foot's frame; the start as in make_reference.py (the rod
             pressed onto the flat line, the corrugation grown in 20 steps, forces normal)
  two contacts, solved by two-segment shooting: unknowns u = (m(0), Fx, Fy, N, T, s_j, X_j,
             m_j) (tip force Cartesian; the side's N, T in the local frame at its lab x X_j;
             the moment m_j at the side). Segment 1 from the foot to s_j carries the tip force
             plus the side's; segment 2 starts at the side on the surface, tangent to it,
             (X_j - d, h(X_j), t(X_j), m_j), and carries the tip force. Residual: segment 1's
             end equals segment 2's start (4), m(1) = 0 and the tip at its lab point (3), and
             the side's mode: sliding T = r N (r = +-mu_k) or rolling sigma(X_j) - s_j = q0.
             The Jacobian, and the state's derivative in d, by complex-step differentiation
             of the residual (the segments integrated over a unit interval scaled by their
             complex length, so that every quantity is an analytic function of u and d).
  touchdown  the two-contact equations with N = T = 0, d unknown (the free rod tangent to the
             surface); seeded by the free rod's smallest clearance on a march in d.
  slip rate  of the side's material point along the surface, q = sigma(X_j) - s_j (the rod runs
             forwards along the surface there): dq/dd from the tangent du/dd = -J^-1 dR/dd. A
             sliding side's friction opposes it: r = +mu_k where q grows (T > 0: towards -x).
             Its sign is chosen so just after touchdown; the halt is where dq/dd = 0 (brentq).
  side slip  where the rolling side's |T|/N reaches mu_s (brentq).

Output `side_reference.csv`: kind (`row` at output d, `touchdown`, `halt`, `side_slip`), d, the
tip's lab x (where it sticks), the side's arc length s_side and lab x x_side, its N and T, the tip's N and T, the total contact
force (fx, fy; the force the rod exerts on its support) and m(0). The tip's |T|/N stays below
mu_s (printed). The script runs at RTOL = 1e-13 and 1e-12 and prints the largest difference.

    pip install scipy; python3 data/drag/make_side_reference.py      (a few minutes)
"""
import csv
import math
import os
import sys

import numpy as np
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq, root

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_reference import Drag, Rod, Sine, Uniform  # noqa: E402

A, LAM, PHASE, ETA = 0.02, 0.2, 4.0, 0.75
MU_S, MU_K = 0.5, 0.3
D_MAX, POINTS = 0.28, 29  # the crate's output grid: d = D_MAX i / (POINTS - 1)
H = 1e-30  # complex step


def h(x):
    return ETA + A * np.sin(2 * np.pi * x / LAM + PHASE)


def dh(x):
    return A * 2 * np.pi / LAM * np.cos(2 * np.pi * x / LAM + PHASE)


def theta(x):
    return np.arctan(dh(x))


def sigma(x):
    """Arc length along the surface from x = 0; analytic continuation to first order for a
    complex-step perturbed x."""
    xr = float(np.real(x))
    v = quad(lambda t: math.sqrt(1 + dh(t) ** 2), 0.0, xr, epsabs=1e-14, epsrel=1e-14, limit=200)[0]
    if np.iscomplexobj(x) or isinstance(x, complex):
        return v + 1j * np.imag(x) * math.sqrt(1 + dh(xr) ** 2)
    return v


class Rod2:
    def __init__(self, rtol):
        self.rtol = rtol

    def seg(self, z0, length, fx, fy, dense=False):
        """Integrates over a segment of (possibly complex) length, in tau in [0, 1]."""
        cplx = any(np.iscomplexobj(np.asarray(v)) for v in (z0, length, fx, fy))
        dt = complex if cplx else float

        def f(t, z):
            c, s = np.cos(z[2]), np.sin(z[2])
            return length * np.array([c, s, z[3], fx * s - fy * c], dtype=dt)
        r = solve_ivp(f, (0.0, 1.0), np.array(z0, dtype=dt), method="DOP853", rtol=self.rtol,
                      atol=self.rtol, dense_output=dense)
        return (r.y[:, -1], r.sol) if dense else r.y[:, -1]


class Scene:
    def __init__(self, rtol):
        self.rod = Rod2(rtol)
        self.rtol = rtol
        self.xa = None

    # -- two contacts ----------------------------------------------------------------------
    def residual(self, u, d, mode):
        m0, fx, fy, nn, tt, sj, xj, mj = u
        th = theta(xj)
        n = (-np.sin(th), np.cos(th))
        t = (-np.cos(th), -np.sin(th))
        sx = -nn * n[0] + tt * t[0]
        sy = -nn * n[1] + tt * t[1]
        z1 = self.rod.seg([0.0, 0.0, math.pi / 2, m0], sj, fx + sx, fy + sy)
        z2s = [xj - d, h(xj), th, mj]
        z2 = self.rod.seg(z2s, 1.0 - sj, fx, fy)
        xa = self.xa
        r = [z1[0] - z2s[0], z1[1] - z2s[1], z1[2] - z2s[2], z1[3] - z2s[3],
             z2[3], z2[0] - (xa - d), z2[1] - h(xa)]
        if mode[0] == "slide":
            r.append(tt - mode[1] * nn)
        elif mode[0] == "roll":
            r.append(sigma(xj) - sj - mode[1])
        else:  # touchdown: N = T = 0 (the unknown d in place of N is handled by the caller)
            r.append(tt)
        return np.array(r)

    def jac(self, u, d, mode):
        """Complex-step Jacobian in u and the derivative in d."""
        u = np.asarray(u, dtype=float)
        cols = []
        for i in range(len(u)):
            uc = u.astype(complex)
            uc[i] += 1j * H
            cols.append(np.imag(self.residual(uc, d, mode)) / H)
        dd = np.imag(self.residual(u.astype(complex), d + 1j * H, mode)) / H
        return np.array(cols).T, dd

    def solve2(self, u, d, mode):
        fun = lambda v: self.residual(v, d, mode)
        r = root(fun, u, jac=lambda v: self.jac(v, d, mode)[0], method="hybr",
                 options={"xtol": 1e-15})
        res = np.max(np.abs(fun(r.x)))
        if res > 1e-12:
            raise RuntimeError(f"two contacts at d = {d}: residual {res:.3e}")
        return r.x

    def rate(self, u, d, mode):
        """dq/dd of the side's material point, q = sigma(X_j) - s_j."""
        j, dd = self.jac(u, d, mode)
        du = -np.linalg.solve(j, dd)
        return math.sqrt(1 + dh(u[6]) ** 2) * du[6] - du[5]

    def touchdown(self, u7):
        """u7 = (m0, Fx, Fy, s_j, X_j, m_j, d): the free rod tangent to the surface."""
        def fun(v, c=False):
            u = np.array([v[0], v[1], v[2], 0.0, 0.0, v[3], v[4], v[5]], dtype=v.dtype)
            return self.residual(u, v[6], ("td",))[:7]

        def jac(v):
            cols = []
            for i in range(7):
                vc = np.asarray(v, dtype=complex)
                vc[i] += 1j * H
                cols.append(np.imag(fun(vc)) / H)
            return np.array(cols).T
        r = root(fun, u7, jac=jac, method="hybr", options={"xtol": 1e-15})
        if np.max(np.abs(fun(r.x))) > 1e-12:
            raise RuntimeError("touchdown not located")
        return r.x

    # -- values of a state --------------------------------------------------------------------
    def values(self, u, d):
        m0, fx, fy, nn, tt, sj, xj, mj = u
        th, ta = theta(xj), theta(self.xa)
        sx = nn * math.sin(th) - tt * math.cos(th)
        sy = -nn * math.cos(th) - tt * math.sin(th)
        ntip = fx * math.sin(ta) - fy * math.cos(ta)
        ttip = -fx * math.cos(ta) - fy * math.sin(ta)
        return dict(d=d, x_tip=self.xa, s_side=sj, x_side=xj, n_side=nn, t_side=tt, n_tip=ntip,
                    t_tip=ttip, fx=fx + sx, fy=fy + sy, m_base=m0)

    def values_tip(self, u, d):
        m0, fx, fy = u
        ta = theta(self.xa)
        return dict(d=d, x_tip=self.xa, s_side="", x_side="", n_side="", t_side="",
                    n_tip=fx * math.sin(ta) - fy * math.cos(ta),
                    t_tip=-fx * math.cos(ta) - fy * math.sin(ta), fx=fx, fy=fy, m_base=m0)

    def clearance(self, u, d, two):
        """Smallest height of the surface above the rod away from the contacts."""
        if two:
            m0, fx, fy, nn, tt, sj, xj, mj = u
            th = theta(xj)
            sx = nn * math.sin(th) - tt * math.cos(th)
            sy = -nn * math.cos(th) - tt * math.sin(th)
            _, s1 = self.rod.seg([0.0, 0.0, math.pi / 2, m0], sj, fx + sx, fy + sy, dense=True)
            _, s2 = self.rod.seg([xj - d, h(xj), th, mj], 1 - sj, fx, fy, dense=True)
            pts = [s1(t) for t in np.linspace(0, 1, 801)[1:-8]]
            pts += [s2(t) for t in np.linspace(0, 1, 201)[8:-4]]
        else:
            m0, fx, fy = u
            _, s1 = self.rod.seg([0.0, 0.0, math.pi / 2, m0], 1.0, fx, fy, dense=True)
            pts = [s1(t) for t in np.linspace(0, 1, 1001)[1:-4]]
        return min(h(z[0] + d) - z[1] for z in pts)

    # -- the run --------------------------------------------------------------------------
    def run(self):
        grid = [D_MAX * i / (POINTS - 1) for i in range(POINTS)]
        drag = Drag(Rod(self.rtol), Sine(ETA, A, LAM, PHASE), Uniform(MU_S, MU_K))
        self.xa, u = drag.start()
        u_start = u
        out, tipmax = [], 0.0
        # tip only: march to the side's touchdown (the free rod's clearance minimum)
        d, gd_prev = 0.0, None
        while True:
            u, mu = drag.stuck(self.xa, d, u)
            _, sol = self.rod.seg([0.0, 0.0, math.pi / 2, u[0]], 1.0, u[1], u[2], dense=True)
            ts = np.linspace(0.5, 0.99, 4901)
            gaps = [h(sol(t)[0] + d) - sol(t)[1] for t in ts]
            k = int(np.argmin(gaps))
            if gaps[k] < 0:
                break
            state = (d, u, ts[k], sol(ts[k]), gaps[k])
            d += 0.002
        d0, u0, s0, z0, g0 = state
        dg = d0 + 0.002 * g0 / (g0 - gaps[k])
        v = self.touchdown(np.array([u0[0], u0[1], u0[2], s0, z0[0] + d0, z0[3], dg]))
        d_td = v[6]
        # the tip-only rows before it
        ut = u_start
        for gd in grid:
            if gd < d_td:
                ut, mu = drag.stuck(self.xa, gd, ut)
                out.append(("row", self.values_tip(ut, gd)))
                tipmax = max(tipmax, abs(mu))
                assert self.clearance(ut, gd, False) > 0
        u = np.array([v[0], v[1], v[2], 0.0, 0.0, v[3], v[4], v[5]])
        out.append(("touchdown", self.values(u, d_td)))
        # the side's friction: the sign whose slip it opposes, just after touchdown
        mode = None
        for r in (MU_K, -MU_K):
            try:
                w = self.solve2(u, d_td + 1e-5, ("slide", r))
            except RuntimeError:
                continue
            q = self.rate(w, d_td + 1e-5, ("slide", r))
            if w[3] > 0 and q * r > 0:
                assert mode is None, "both signs consistent"
                mode = ("slide", r)
        assert mode is not None, "no sliding side consistent with its slip"
        # the rolling side would need more than mu_s at once (why it slides)
        q0 = sigma(u[6]) - u[5]
        w = self.solve2(u, d_td + 1e-5, ("roll", q0))
        print(f"rolling side just after touchdown: |T|/N = {abs(w[4] / w[3]):.3e}",
              file=sys.stderr)
        # slide: march, halt where the slip rate vanishes
        cache = {d_td: u}

        def state(dd, md):
            best = min(cache, key=lambda c: abs(c - dd))
            uu = self.solve2(cache[best], dd, md)
            cache[dd] = uu
            return uu
        d, halt = d_td, None
        rate_of = lambda dd: self.rate(state(dd, mode), dd, mode) * np.sign(mode[1])
        while halt is None:
            dn = min(d + 0.002, D_MAX)
            if rate_of(dn) <= 0:
                halt = brentq(rate_of, d, dn, xtol=1e-15, rtol=1e-15)
            d = dn
        for gd in grid:
            if d_td < gd < halt:
                uu = state(gd, mode)
                out.append(("row", self.values(uu, gd)))
                assert self.clearance(uu, gd, True) > 0
        u = state(halt, mode)
        out.append(("halt", self.values(u, halt)))
        # roll: from the halt on, up to the side's own slip limit
        mode = ("roll", float(sigma(u[6]) - u[5]))
        cache = {halt: u}
        lim = lambda dd: abs(state(dd, mode)[4] / state(dd, mode)[3]) - MU_S
        d, slip = halt, None
        while slip is None:
            dn = d + 0.002
            if lim(dn) >= 0:
                slip = brentq(lim, d, dn, xtol=1e-15, rtol=1e-15)
            d = dn
        for gd in grid:
            if halt < gd < slip:
                uu = state(gd, mode)
                out.append(("row", self.values(uu, gd)))
                assert self.clearance(uu, gd, True) > 0
        out.append(("side_slip", self.values(state(slip, mode), slip)))
        out.sort(key=lambda r: r[1]["d"])
        for kind, v in out:
            if v["s_side"] != "":
                tipmax = max(tipmax, abs(v["t_tip"] / v["n_tip"]))
                assert v["n_side"] >= 0 and v["n_tip"] > 0
        print(f"rtol {self.rtol}: touchdown {d_td}, halt {halt}, side slip {slip}; largest tip "
              f"|T|/N {tipmax:.6f} (mu_s {MU_S})", file=sys.stderr)
        return out


COLS = ["d", "x_tip", "s_side", "x_side", "n_side", "t_side", "n_tip", "t_tip", "fx", "fy",
        "m_base"]


def halt_of(rows):
    return next(v["d"] for kind, v in rows if kind == "halt")


def main():
    tols = [float(t) for t in os.environ.get("RTOLS", "1e-13,1e-12").split(",")]
    a, b = (Scene(rtol).run() for rtol in tols)
    assert [r[0] for r in a] == [r[0] for r in b]
    spread = {}
    for (kind, p), (_, q) in zip(a, b):
        part = "slide" if kind in ("row", "touchdown") and p["d"] < halt_of(a) else kind
        part = "roll" if kind == "row" and p["d"] > halt_of(a) else part
        for c in COLS:
            if p[c] != "":
                spread[part] = max(spread.get(part, 0.0), abs(p[c] - q[c]))
    with open("data/drag/side_reference.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["kind"] + COLS)
        for kind, v in a:
            w.writerow([kind] + [repr(float(v[c])) if v[c] != "" else "" for c in COLS])
    print(f"largest change of any value from rtol {tols[0]} to {tols[1]}: "
          + ", ".join(f"{k} {v:.3e}" for k, v in spread.items()), file=sys.stderr)


if __name__ == "__main__":
    main()
