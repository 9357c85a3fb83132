#!/usr/bin/env python3
"""Independent reference of a stretch of the rod lying on a curved surface (issue 31), for crate
`vibrissa` (crates/vibrissa/tests/stretch.rs, `a_lying_stretch_matches_the_independent_reference`).

Scene: the clamped rod tapered to 0.3 (b(s) = 1/EI = (1 - 0.7 s)^-4), straight at rest, surface
h(x) = 0.75 + 0.001 sin(2 pi x / 0.5 + 4 pi / 3), mu_s = 0.5, mu_k = 0.3 (crate: `drag --taper 0.3
--eta 0.75 --mu-s 0.5 --mu-k 0.3 --corrugation-amplitude 0.001 --corrugation-wavelength 0.5
--corrugation-phase 4.1887902047863905 --d-max 0.3`). The pressed rod touches the surface with
its side only, the rest beyond unloaded. Rolling without slip as the foot moves, that side reaches
the corrugation's inflection x2 = 5/12 at d = 0.0070376, where the rod's curvature at it (zero:
the unloaded rest beyond) equals the surface's. From there a stretch of the rod lies on the
surface: from s1 out to the material point s2 that reached the inflection, which stays there
(the rest beyond it is unloaded, so the moment there is zero, and so is the surface's
curvature). The stretch grows towards the foot.

Input from the crate: s2 = 0.9658524852769022, the arc length of the side when it reached the
inflection (it depends on the pressed start and the rolling before, which this script does not
follow); the test checks the crate's value against it. Everything else is this script's own.

Rod (normalized units, arc length s from the foot; none of the crate's code):

    x' = cos(phi),  y' = sin(phi),  phi' = b(s) m,  m' = Fx sin(phi) - Fy cos(phi)
    x(0) = d, y(0) = 0, phi(0) = pi/2     (lab frame: the foot at (d, 0), the surface above)

F = (Fx, Fy) the resultant of the stretch's contact forces on the rod (the force on [0, s1]).
Unknowns u = (m(0), Fx, Fy, s1); conditions at s1, where the rod arrives on the surface:
    X1 from sigma(X1) = sigma(x2) - (s2 - s1)        (no slip: arc lengths along rod and surface)
    x(s1) = X1, y(s1) = h(X1), phi(s1) = atan h'(X1),
    b(s1) m(s1) = kappa_s(X1) = h''/(1 + h'^2)^(3/2)  (the rod lies with the surface's curvature)
integrated by scipy's DOP853 (`solve_ivp`, rtol = atol = RTOL), sigma by `quad`, solved by
`root` (hybr) from a rough guess at d = 0.05 and continued in d.

Output `stretch_reference.csv`: kind (`row` at d = 0.05, 0.1, ..., 0.7; `peel_up` where the
stretch has shrunk back to its outer end, s1 = s2, found with d as the unknown), d, s1, X1, the resultant's normal and tangential parts in the
surface's frame at X1 (n = (-sin t, cos t) into the surface, t_ = -(cos t, sin t), F = -N n + T t_,
t = atan h'(X1)), Fx, Fy, m(0), and checks: P1 and P2, the point forces at the stretch's inner and
outer ends (the jumps of the internal force's normal part: P1 = m'(s1-) - m'(s1+),
P2 = m'(s2-) with m = kappa_s / b on the stretch), which must push (> 0), and the smallest gap
h(x) - y of the free rod on [0, s1] (>= 0: no penetration).

    pip install scipy; python3 data/drag/make_stretch_reference.py      (about a minute)
"""
import csv
import math
import os

import numpy as np
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq, root

A, W, PHASE, ETA = 0.001, 0.5, 4 * math.pi / 3, 0.75
RHO = 0.3
S2 = 0.9658524852769022
X2 = 5.0 / 12.0
K = 2 * math.pi / W
D_OUT = [round(0.05 * k, 2) for k in range(1, 15)]  # 0.05 ... 0.7


def h(x):
    return ETA + A * math.sin(K * x + PHASE)


def dh(x):
    return A * K * math.cos(K * x + PHASE)


def ddh(x):
    return -A * K * K * math.sin(K * x + PHASE)


def dddh(x):
    return -A * K ** 3 * math.cos(K * x + PHASE)


def kappa_s(x):
    return ddh(x) / (1 + dh(x) ** 2) ** 1.5


def dkappa_s(x):
    d1, d2, d3 = dh(x), ddh(x), dddh(x)
    return d3 / (1 + d1 * d1) ** 1.5 - 3 * d1 * d2 * d2 / (1 + d1 * d1) ** 2.5


def b(s):
    return (1 - (1 - RHO) * s) ** -4


def db(s):
    return 4 * (1 - RHO) * (1 - (1 - RHO) * s) ** -5


def sigma(x):
    return quad(lambda t: math.sqrt(1 + dh(t) ** 2), 0.0, x, epsabs=1e-13, epsrel=1e-13,
                limit=200)[0]


SIG2 = sigma(X2)


def x_of_s(s):
    """Lab x of the material point s on the stretch."""
    target = SIG2 - (S2 - s)
    return brentq(lambda x: sigma(x) - target, X2 - 0.3, X2 + 0.1, xtol=1e-15, rtol=1e-15)


class Rod:
    def __init__(self, rtol):
        self.rtol = rtol

    def shoot(self, u, d, dense=False):
        m0, fx, fy, s1 = u

        def f(s, z):
            c, sn = math.cos(z[2]), math.sin(z[2])
            return [c, sn, b(s) * z[3], fx * sn - fy * c]
        r = solve_ivp(f, (0.0, s1), [d, 0.0, math.pi / 2, m0], method="DOP853", rtol=self.rtol,
                      atol=self.rtol, dense_output=dense)
        return r

    def residual(self, u, d):
        s1 = u[3]
        z = self.shoot(u, d).y[:, -1]
        x1 = x_of_s(s1)
        return [z[0] - x1, z[1] - h(x1), z[2] - math.atan(dh(x1)), b(s1) * z[3] - kappa_s(x1)]

    def solve(self, d, guess):
        r = root(lambda u: self.residual(u, d), guess, method="hybr", options={"xtol": 1e-15})
        res = max(abs(v) for v in self.residual(r.x, d))
        if res > 1e-11:
            raise RuntimeError(f"no convergence at d = {d}: residual {res:.3e}")
        return r.x

    def row(self, d, u):
        m0, fx, fy, s1 = u
        x1 = x_of_s(s1)
        t = math.atan(dh(x1))
        n, tt = (-math.sin(t), math.cos(t)), (-math.cos(t), -math.sin(t))
        nn = -(fx * n[0] + fy * n[1])
        tn = fx * tt[0] + fy * tt[1]
        r = self.shoot(u, d, dense=True)
        z1 = r.y[:, -1]
        # m' on either side of the inner end; on the stretch m = kappa_s(x(s)) / b(s), dx/ds = cos t
        m_in = fx * math.sin(z1[2]) - fy * math.cos(z1[2])
        m_st = lambda s, x: dkappa_s(x) * math.cos(math.atan(dh(x))) / b(s) \
            - kappa_s(x) * db(s) / b(s) ** 2
        p1 = m_in - m_st(s1, x1)
        p2 = m_st(S2, X2)
        gaps = [h(z[0]) - z[1] for z in (r.sol(s) for s in np.linspace(0.0, s1, 2001))]
        return dict(d=d, s1=s1, x1=x1, normal=nn, tangential=tn, fx=fx, fy=fy, m_base=m0,
                    p1=p1, p2=p2, min_gap=min(gaps))


def run(rtol):
    rod = Rod(rtol)
    guess = [-0.026, -0.59, -1.43, 0.927]
    rows = []
    for d in D_OUT:
        u = rod.solve(d, guess)
        rows.append(dict(rod.row(d, u), kind="row"))
        guess = u
    # the peel-up: the stretch shrinks back to its outer end (s1 = s2), d unknown
    def peel(v):
        m0, fx, fy, d = v
        return rod.residual([m0, fx, fy, S2], d)
    r = root(peel, [guess[0], guess[1], guess[2], D_OUT[-1]], method="hybr",
             options={"xtol": 1e-15})
    if max(abs(v) for v in peel(r.x)) > 1e-11:
        raise RuntimeError("the peel-up did not converge")
    m0, fx, fy, d = r.x
    rows.append(dict(rod.row(d, [m0, fx, fy, S2]), kind="peel_up"))
    return rows


# -- the stretch with the tip stuck beyond it ---------------------------------------------------
#
# Scene 2: the same rod over h(x) = 0.75 + 0.003 sin(2 pi x / 0.5 + 2.4) (crate: `--corrugation-
# amplitude 0.003 --corrugation-wavelength 0.5 --corrugation-phase 2.4`), where the side that
# lies down at d = 0.1391131 has the tip stuck on the surface beyond it. Inputs from the crate:
# the side's arc length and lab x when it lay down (S2B, X2B: its rolling invariant
# c = sigma(X2B) - S2B) and the tip's lab x, where it sticks (XA). Unknowns (m(0), Fx, Fy, s1, s2,
# Gx, Gy): F the total contact force (on [0, s1]), G the tip's (on [s2, 1]). Conditions: the four
# at s1 as above (the stretch's rolling invariant c); the segment beyond starts at s2 on the
# surface (x from sigma(x) = c + s2, tangent, m = kappa_s / b) and ends at the tip's place with
# m(1) = 0.
A_B, PHASE_B = 0.003, 2.4
S2B, X2B = 0.9328532248245588, 0.4785523319061838
XA = 0.545667226423673
D_OUT_B = [0.15, 0.2, 0.25, 0.3]


class Sine:
    def __init__(self, a, phase):
        self.a, self.phase = a, phase

    def h(self, x):
        return ETA + self.a * math.sin(K * x + self.phase)

    def dh(self, x):
        return self.a * K * math.cos(K * x + self.phase)

    def kappa(self, x):
        d1 = self.dh(x)
        d2 = -self.a * K * K * math.sin(K * x + self.phase)
        return d2 / (1 + d1 * d1) ** 1.5

    def sigma(self, x):
        return quad(lambda t: math.sqrt(1 + self.dh(t) ** 2), 0.0, x, epsabs=1e-13,
                    epsrel=1e-13, limit=200)[0]

    def x_at(self, target, guess):
        return brentq(lambda x: self.sigma(x) - target, guess - 0.3, guess + 0.3, xtol=1e-15,
                      rtol=1e-15)


class TipBeyond:
    def __init__(self, rtol):
        self.rtol = rtol
        self.surf = Sine(A_B, PHASE_B)
        self.c = self.surf.sigma(X2B) - S2B

    def seg(self, z0, a, b_, fx, fy):
        def f(s, z):
            c, sn = math.cos(z[2]), math.sin(z[2])
            return [c, sn, b(s) * z[3], fx * sn - fy * c]
        return solve_ivp(f, (a, b_), z0, method="DOP853", rtol=self.rtol,
                         atol=self.rtol).y[:, -1]

    def residual(self, u, d):
        m0, fx, fy, s1, s2, gx, gy = u
        sf = self.surf
        z1 = self.seg([d, 0.0, math.pi / 2, m0], 0.0, s1, fx, fy)
        x1 = sf.x_at(self.c + s1, X2B)
        x2 = sf.x_at(self.c + s2, X2B)
        z2 = self.seg([x2, sf.h(x2), math.atan(sf.dh(x2)), sf.kappa(x2) / b(s2)], s2, 1.0, gx, gy)
        return [z1[0] - x1, z1[1] - sf.h(x1), z1[2] - math.atan(sf.dh(x1)),
                b(s1) * z1[3] - sf.kappa(x1), z2[0] - XA, z2[1] - sf.h(XA), z2[3]]

    def solve(self, d, guess):
        r = root(lambda u: self.residual(u, d), guess, method="hybr", options={"xtol": 1e-15})
        res = max(abs(v) for v in self.residual(r.x, d))
        if res > 1e-11:
            raise RuntimeError(f"no convergence at d = {d}: residual {res:.3e}")
        return r.x

    def row(self, d, u):
        m0, fx, fy, s1, s2, gx, gy = u
        sf = self.surf
        x1 = sf.x_at(self.c + s1, X2B)

        def local(gx_, gy_, x):
            t = math.atan(sf.dh(x))
            n, tt = (-math.sin(t), math.cos(t)), (-math.cos(t), -math.sin(t))
            return -(gx_ * n[0] + gy_ * n[1]), gx_ * tt[0] + gy_ * tt[1]
        ns, ts = local(fx - gx, fy - gy, x1)
        nt, tn = local(gx, gy, XA)
        return dict(kind="row", d=d, s1=s1, s2=s2, n_stretch=ns, t_stretch=ts, n_tip=nt,
                    t_tip=tn, fx=fx, fy=fy, m_base=m0)


def run_b(rtol):
    sc = TipBeyond(rtol)
    t = math.atan(sc.surf.dh(XA))
    n, tt = (-math.sin(t), math.cos(t)), (-math.cos(t), -math.sin(t))
    gx, gy = -0.0868 * n[0] + 0.0284 * tt[0], -0.0868 * n[1] + 0.0284 * tt[1]
    guess = [-0.0117, -0.606, -1.442, 0.9242, 0.93285, gx, gy]
    rows = []
    for d in D_OUT_B:
        u = sc.solve(d, guess)
        rows.append(sc.row(d, u))
        guess = u
    return rows


def write(name, cols, rows, check, compared):
    """Writes `rows` (`kind`, then `cols`) to `name` beside this script; prints the largest
    change of the `compared` columns against `check` (the same at rtol 1e-12)."""
    worst = max(abs(a[c] - b_[c]) for a, b_ in zip(rows, check) for c in compared)
    print(f"{name}: largest change of any value from rtol 1e-13 to 1e-12: {worst:.2e}")
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), name)
    with open(out, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["kind"] + cols)
        for r in rows:
            w.writerow([r["kind"]] + [repr(float(r[c])) for c in cols])


def main():
    cols = ["d", "s1", "s2", "n_stretch", "t_stretch", "n_tip", "t_tip", "fx", "fy", "m_base"]
    rows = run_b(1e-13)
    write("stretch_tip_reference.csv", cols, rows, run_b(1e-12), cols)
    for r in rows:
        print(f"d {r['d']}: s1 {r['s1']:.9f} s2 {r['s2']:.12f} tip N {r['n_tip']:.10f} "
              f"T {r['t_tip']:.10f}")
    cols = ["d", "s1", "x1", "normal", "tangential", "fx", "fy", "m_base", "p1", "p2", "min_gap"]
    rows = run(1e-13)
    write("stretch_reference.csv", cols, rows, run(1e-12), cols[:8])
    for r in rows:
        print(f"{r['kind']} d {r['d']}: s1 {r['s1']:.9f}, "
              f"|T|/N {abs(r['tangential'] / r['normal']):.6f}, "
              f"P1 {r['p1']:.4e}, P2 {r['p2']:.4e}, min gap {r['min_gap']:.2e}")


if __name__ == "__main__":
    main()
