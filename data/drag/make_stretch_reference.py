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

Scene 3, the stretch slipping (`stretch_slip_reference.csv`; code below `run_b`): scene 1's rod
and surface with mu_s = 0.42, in two variants, mu_k = 0.3 and mu_k = 0.38. The stretch lies down
as in scene 1 (the same input s2) and is dragged on stuck: its rolling invariant c = sigma(x2) - s2
fixed (the material point s at the x with sigma(x) = c + s), its outer end at the inflection x2
whatever material point is there (the rest beyond unloaded, m = 0, and so the surface's
curvature): s2 = sigma(x2) - c. Up to the first slip this is scene 1.

On the stretch the rod follows the surface: t = atan h'(x), kappa = kappa_s(x) = b m, dx/ds =
cos t = (1 + h'^2)^-1/2, so m = kappa_s / b, and m', m'' (in s) are closed forms (kappa_s'' from
the fourth derivative A K^4 sin(K x + phase); no finite differences). The surface's force on the
rod: p (-n) + f e per unit length, P1 (-n) + F1 e at s1, P2 (-n) + F2 e at s2 (e = (cos t, sin t),
n = (-sin t, cos t); p, P1, P2 >= 0, the surface above pushes). G(s), the force of the rod beyond
s on [0, s] (F on [0, s1], 0 beyond s2): G' = -(p (-n) + f e) on the stretch (equilibrium of
[s, s + ds]) and m' = Gx sin t - Gy cos t = -G.n. With G = Ge e + Gn n, e' = kappa n,
n' = -kappa e:

    Gn = -m',   p = -m'' + kappa Ge,   Ge' = -kappa m' - f,
    P2 = m'(s2-), Ge(s2-) = F2,   P1 = m'(s1-) - m'(s1+),   F.e(x1) = Ge(s1+) + F1,

m'(s1-) = Fx sin t1 - Fy cos t1 from the free rod. A slide moves every material point of the
stretch by the same arc length along the surface, c -> c + g a (a > 0; g = +1 towards +x), and
kinetic friction opposes it everywhere: f = -g mu p, F1 = -g mu P1, F2 = -g mu P2. Then

    Ge' = -kappa m' + g mu (kappa Ge - m''),   Ge(s2) = -g mu P2,

integrated from the outer end in to s1 (DOP853 in lab x from x2 to x1, s a state with ds/dx =
(1 + h'^2)^1/2), and the balance's margin M_g(mu) = g (F.e(x1) - Ge(s1+) + g mu P1), F from the
stuck equilibrium (scene 1's four conditions at s1, with this c). Stuck, the friction is
statically indeterminate and reaches at most the capstan distribution with mu_s, either way: the
stretch holds while M_+1(mu_s) >= 0 and M_-1(mu_s) >= 0 and slips in the direction g whose margin
reaches 0 (the threshold, d unknown; found g = +1: the foot drives the stretch towards +x, and
M_-1 stays far from 0). The slide, the foot held: the first a > 0 where the stuck equilibrium at
c + g a is balanced by kinetic friction, M_g(mu_k) = 0 (a unknown); then the drag goes on stuck at
the new c to the next threshold. Scans bracket a threshold (d in steps of 0.002) and a
slide (a in steps of 0.001), brentq finds it, hybr polishes it with d or a as a fifth unknown.
Checked aside (not in the script): dE/dc at fixed d = F.e - int kappa m' ds over the stretch (the
virtual work of its friction), to 1e-9 by central differences.

What is computed, for each mu_k (a variant, from the lie-down's c; the stick phase and the first
threshold are the same in both): the stuck stretch at d = 0.04; then the drag from d = 0.05 on to
a threshold, its slide, and again, up to three thresholds (the third without its slide); a
variant stops earlier at a slide that shrinks the stretch to its outer end, or where d passes 0.3
(or the stuck stretch shrinks to its outer end) before the next threshold.
  mu_k = 0.3: the first slide ends the stretch: `stick`, `slip`, `slide_peel_up` (no second slip).
  mu_k = 0.38: each slide ends with the stretch intact, balanced by kinetic friction: `stick`,
  `slip`, `slid`, `slip`, `slid`, `slip`.

Output, the mu_k = 0.3 rows first, then the mu_k = 0.38 rows, each variant in the order of the
drag: kind (`stick`: the stuck stretch at d = 0.04, at its lie-down invariant, before the first
slip; `slip`: a threshold; `slid`: where its slide ends, kinetic balance reached with the stretch
intact; `slide_peel_up`: where the slide has shrunk the stretch to its outer end, s1 = s2 at x2,
with mu_k not yet balancing it: the rod slides on with a point there, beyond this model, and the
variant stops), mu_k, d, s1, x1, shift (the slides so far, cumulative within the variant:
c - (sigma(x2) - s2 of the lie-down), 0 up to its first slide; a `slip` row carries the shift of
the slides before it, its `slid` row adds its own), normal, tangential, fx, fy, m_base (as in
scene 1), s2, energy (int b m^2 / 2 over [0, s2], the stretch included), p1, p2, pmin (the
smallest p on the stretch under the row's distribution: mu_s at a slip, mu_k after a slide; 0.0
in `stick` rows, where the friction is indeterminate and instead both margins M_+1(mu_s) and
M_-1(mu_s) are checked >= 0), released (the energy at the slip less the energy after its slide,
in `slid` and `slide_peel_up` rows; 0.0 in `stick` and `slip` rows). A row with s1 > s2, p, P1 or
P2 < 0, or the free rod crossing the surface stops the script. The whole file is computed again
at rtol 1e-12 (the same rows, else the script stops) and its largest change printed.

    pip install scipy; python3 data/drag/make_stretch_reference.py      (about 15 seconds)
"""
import csv
import math
import os

import numpy as np
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq, minimize_scalar, root

A, W, PHASE, ETA = 0.001, 0.5, 4 * math.pi / 3, 0.75
RHO = 0.3
S2 = 0.9658524852769022
X2 = 5.0 / 12.0
K = 2 * math.pi / W
D_OUT = [round(0.05 * k, 2) for k in range(1, 15)]  # 0.05 ... 0.7


def solved(f, guess, what):
    """The root of f near guess (scipy's hybr, xtol 1e-15), its residual at most 1e-11, else
    an error naming what did not converge."""
    r = root(f, guess, method="hybr", options={"xtol": 1e-15})
    res = max(abs(v) for v in f(r.x))
    if res > 1e-11:
        raise RuntimeError(f"{what} did not converge: residual {res:.3e}")
    return r.x


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
        return solved(lambda u: self.residual(u, d), guess, f"the state at d = {d}")

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
    m0, fx, fy, d = solved(peel, [guess[0], guess[1], guess[2], D_OUT[-1]], "the peel-up")
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
S2B, X2B = 0.9328531919102035, 0.47855232184548324
XA = 0.5456672492594945
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
        return solved(lambda u: self.residual(u, d), guess, f"the state at d = {d}")

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


# -- the stretch slipping (scene 3) -------------------------------------------------------------
#
# Scene 1's rod and surface with mu_s = 0.42 and each of mu_k = 0.3, 0.38 (a variant each); the
# stretch's rolling invariant c = sigma(x) - s an unknown of the slides (see the module's
# docstring, "Scene 3").
MU_S3, MU_K3 = 0.42, (0.3, 0.38)
D_STICK3, D_MAX3, SLIPS3 = 0.04, 0.3, 3  # the stick row's d; a variant stops beyond D_MAX3 or
# at its SLIPS3-th slip


def d4h(x):
    return A * K ** 4 * math.sin(K * x + PHASE)


def ddkappa_s(x):
    d1, d2, d3, d4 = dh(x), ddh(x), dddh(x), d4h(x)
    q = 1 + d1 * d1
    return d4 / q ** 1.5 - 3 * (3 * d1 * d2 * d3 + d2 ** 3) / q ** 2.5 \
        + 15 * d1 * d1 * d2 ** 3 / q ** 3.5


def m_lying(x, s):
    """m, dm/ds and d2m/ds2 of the rod lying on the surface at lab x (material point s):
    m = kappa_s(x) w(s), w = 1/b = (1 - 0.7 s)^4, dx/ds = cos t = (1 + h'^2)^-1/2."""
    a = 1 - RHO
    v = 1 - a * s
    w, w1, w2 = v ** 4, -4 * a * v ** 3, 12 * a * a * v * v
    q = 1 + dh(x) ** 2
    ct, dct = q ** -0.5, -dh(x) * ddh(x) * q ** -1.5  # cos t and d(cos t)/dx
    k, k1 = kappa_s(x), dkappa_s(x)
    ks, kss = k1 * ct, ct * (ddkappa_s(x) * ct + k1 * dct)  # d kappa/ds, d2 kappa/ds2
    return k * w, ks * w + k * w1, kss * w + 2 * ks * w1 + k * w2


class Slip:
    D_STEP, C_STEP = 0.002, 0.001  # the scans that bracket a threshold (in d) and a slide (in c)

    def __init__(self, rtol):
        self.rtol = rtol
        self.rod = Rod(rtol)

    @staticmethod
    def x_at(c, s):
        """Lab x of the material point s on the surface: sigma(x) = c + s."""
        return brentq(lambda x: sigma(x) - (c + s), X2 - 0.3, X2 + 0.1, xtol=1e-15, rtol=1e-15)

    def residual(self, u, d, c):
        s1 = u[3]
        z = self.rod.shoot(u, d).y[:, -1]
        x1 = self.x_at(c, s1)
        return [z[0] - x1, z[1] - h(x1), z[2] - math.atan(dh(x1)), b(s1) * z[3] - kappa_s(x1)]

    def solve(self, d, c, guess):
        return solved(lambda u: self.residual(u, d, c), guess, f"the state at d = {d}, c = {c}")

    def stretch(self, c, x1, mu, g, dense=False):
        """The stretch from its outer end (lab X2, s2 = sigma(X2) - c) in to x1 under the
        friction f = -g mu p, F2 = -g mu P2: (G_e(s1+), its energy, P2, the solution in x of
        (s, G_e, energy from X2), None without a stretch)."""
        s2 = SIG2 - c
        p2 = m_lying(X2, s2)[1]
        if x1 > X2 - 1e-14:
            return -g * mu * p2, 0.0, p2, None

        def f(x, z):
            dsdx = math.sqrt(1 + dh(x) ** 2)
            k = kappa_s(x)
            m, m1, m2 = m_lying(x, z[0])
            p = -m2 + k * z[1]
            return [dsdx, (-k * m1 + g * mu * p) * dsdx, k * m / 2 * dsdx]  # k m = b m^2
        r = solve_ivp(f, (X2, x1), [s2, -g * mu * p2, 0.0], method="DOP853", rtol=self.rtol,
                      atol=self.rtol, dense_output=dense)
        return r.y[1, -1], -r.y[2, -1], p2, r

    def margin(self, u, c, mu, g):
        """g (F.e - (G_e(s1+) + F1)) with the distribution f = -g mu p, F1,2 = -g mu P1,2:
        >= 0 for both g while the stretch holds with mu = mu_s; 0 where it is balanced."""
        m0, fx, fy, s1 = u
        x1 = self.x_at(c, s1)
        t1 = math.atan(dh(x1))
        ge1 = self.stretch(c, x1, mu, g)[0]
        p1 = fx * math.sin(t1) - fy * math.cos(t1) - m_lying(x1, s1)[1]
        return g * (fx * math.cos(t1) + fy * math.sin(t1) - (ge1 - g * mu * p1))

    def polish(self, u, fixed, unknown, mu, g):
        """Polishes u with one more unknown: d (unknown = 'd', c fixed) or the slide a
        (unknown = 'a', d = fixed[0], c = fixed[1] + g a), the margin with mu the condition."""
        def split(v):
            if unknown == "d":
                return v[:4], v[4], fixed
            return v[:4], fixed[0], fixed[1] + g * v[4]

        def eqs(v):
            w, d, c = split(v)
            return self.residual(w, d, c) + [self.margin(w, c, mu, g)]
        return solved(eqs, u, f"the polish in {unknown}")

    def threshold(self, d, c, u):
        """Drags the stuck stretch (c fixed) from d on to the mu_s threshold: (d, u, g), or None
        if d passes D_MAX3 first or the stretch shrinks to its outer end first (s1 = s2)."""
        while True:
            if d >= D_MAX3:
                return None
            d_new = d + self.D_STEP
            u_new = self.solve(d_new, c, u)
            if u_new[3] >= SIG2 - c:
                return None
            low = [g for g in (1, -1) if self.margin(u_new, c, MU_S3, g) < 0]
            if low:
                break
            d, u = d_new, u_new
        g = low[0]
        guess = [u]

        def f(dd):
            guess[0] = self.solve(dd, c, guess[0])
            return self.margin(guess[0], c, MU_S3, g)
        d = brentq(f, d, d_new, xtol=1e-15, rtol=1e-15)
        v = self.polish(list(self.solve(d, c, guess[0])) + [d], c, "d", MU_S3, g)
        if v[4] > D_MAX3:
            return None
        return v[4], v[:4], g

    def slide(self, d, c, u, g, mu):
        """Slides the stretch (c -> c + g a, d held) to the first a > 0 where mu balances it:
        (a, u, False), or to where its inner end reaches its outer end first (s1 = s2):
        (a, u, True)."""
        a = 0.0
        while True:
            a_new = a + self.C_STEP
            u_new = self.solve(d, c + g * a_new, u)
            if u_new[3] >= SIG2 - (c + g * a_new):  # s1 >= s2: the stretch is gone
                def peel(v):
                    return self.residual([v[0], v[1], v[2], SIG2 - c - g * v[3]], d,
                                         c + g * v[3])
                v = solved(peel, list(u[:3]) + [a], "the slide's peel-up")
                a_p = v[3]
                u_p = [v[0], v[1], v[2], SIG2 - c - g * a_p]
                if self.margin(u_p, c + g * a_p, mu, g) < 0:
                    return a_p, u_p, True
                a_new, u_new = a_p, u_p  # balanced before the stretch is gone
            if self.margin(u_new, c + g * a_new, mu, g) >= 0:
                break
            a, u = a_new, u_new
        guess = [u]

        def f(aa):
            guess[0] = self.solve(d, c + g * aa, guess[0])
            return self.margin(guess[0], c + g * aa, mu, g)
        a = brentq(f, a, a_new, xtol=1e-15, rtol=1e-15)
        v = self.polish(list(self.solve(d, c + g * a, guess[0])) + [a], (d, c), "a", mu, g)
        return v[4], v[:4], False

    def row(self, kind, d, c, u, mu, g, shift):
        """The row at (d, c, u); mu, g: the friction distribution of pmin (mu None: stuck, the
        distribution indeterminate, pmin = 0.0 and the margins with mu_s checked instead)."""
        m0, fx, fy, s1 = u
        s2 = SIG2 - c
        x1 = self.x_at(c, s1)
        t = math.atan(dh(x1))
        n, tt = (-math.sin(t), math.cos(t)), (-math.cos(t), -math.sin(t))
        nn = -(fx * n[0] + fy * n[1])
        tn = fx * tt[0] + fy * tt[1]

        def f(s, z):  # the free rod with its energy
            cs, sn = math.cos(z[2]), math.sin(z[2])
            return [cs, sn, b(s) * z[3], fx * sn - fy * cs, b(s) * z[3] ** 2 / 2]
        r = solve_ivp(f, (0.0, s1), [d, 0.0, math.pi / 2, m0, 0.0], method="DOP853",
                      rtol=self.rtol, atol=self.rtol, dense_output=True)
        gaps = [h(z[0]) - z[1] for z in (r.sol(s) for s in np.linspace(0.0, s1, 2001))]
        # the energy and P2 do not depend on the distribution (mu = 0 for the stick row)
        ge1, e_st, p2, st = self.stretch(c, x1, 0.0 if mu is None else mu, g, dense=True)
        p1 = fx * math.sin(t) - fy * math.cos(t) - m_lying(x1, s1)[1]
        if mu is None:
            pmin = 0.0
            if min(self.margin(u, c, MU_S3, gg) for gg in (1, -1)) < 0:
                raise RuntimeError(f"{kind} at d = {d}: the stretch does not hold")
        elif st is None:
            pmin = -m_lying(X2, s2)[2]
        else:
            def p(x):
                z = st.sol(x)
                return -m_lying(x, z[0])[2] + kappa_s(x) * z[1]
            xs = np.linspace(x1, X2, 2001)
            ps = [p(x) for x in xs]
            i = int(np.argmin(ps))
            pmin = ps[i]
            if 0 < i < len(xs) - 1:
                pmin = min(pmin, minimize_scalar(p, bounds=(xs[i - 1], xs[i + 1]),
                                                 method="bounded",
                                                 options={"xatol": 1e-14}).fun)
        if s1 > s2 + 1e-12 or min(p1, p2, pmin) < 0 or min(gaps) < -1e-12:
            raise RuntimeError(f"{kind} at d = {d}: the model does not hold (s1 {s1}, s2 {s2}, "
                               f"P1 {p1}, P2 {p2}, p {pmin}, gap {min(gaps)})")
        return dict(kind=kind, d=d, s1=s1, x1=x1, shift=shift, normal=nn, tangential=tn, fx=fx,
                    fy=fy, m_base=m0, s2=s2, energy=r.y[4, -1] + e_st, p1=p1, p2=p2, pmin=pmin,
                    released=0.0, min_gap=min(gaps), g=g)


def run_c(rtol, mu_k):
    """Scene 3 with this mu_k: the stick row, then up to SLIPS3 slips, each but the last with its
    slide; (rows, why the variant stopped)."""
    sc = Slip(rtol)
    c, shift = SIG2 - S2, 0.0
    guess = [-0.026, -0.59, -1.43, 0.927]
    u = sc.solve(D_STICK3, c, guess)
    rows = [sc.row("stick", D_STICK3, c, u, None, 0, shift)]
    d = 0.05
    u = sc.solve(d, c, guess)
    stop = f"{SLIPS3} slips"
    for k in range(SLIPS3):
        t = sc.threshold(d, c, u)
        if t is None:
            stop = f"no slip up to d = {D_MAX3} (or the stuck stretch gone) after {k} slips"
            break
        d, u, g = t
        slip = sc.row("slip", d, c, u, MU_S3, g, shift)
        rows.append(slip)
        if k == SLIPS3 - 1:
            break
        a, u, gone = sc.slide(d, c, u, g, mu_k)
        c, shift = c + g * a, shift + g * a
        end = sc.row("slide_peel_up" if gone else "slid", d, c, u, mu_k, g, shift)
        end["released"] = slip["energy"] - end["energy"]
        rows.append(end)
        if gone:
            stop = ("the slide shrank the stretch to its outer end (s1 = s2) before mu_k balanced "
                    "it; the rod slides on with a point at the inflection, beyond this model")
            break
    for r in rows:
        r["mu_k"] = mu_k
    return rows, stop


def write(name, cols, rows, check, compared):
    """Writes `rows` (`kind`, then `cols`) to `name` beside this script; prints the largest
    change of the `compared` columns against `check` (the same at rtol 1e-12)."""
    if [r["kind"] for r in rows] != [r["kind"] for r in check]:
        raise RuntimeError(f"{name}: the rows differ between rtol 1e-13 and 1e-12")
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
    cols = ["mu_k", "d", "s1", "x1", "shift", "normal", "tangential", "fx", "fy", "m_base", "s2",
            "energy", "p1", "p2", "pmin", "released"]
    runs = [run_c(1e-13, mu) for mu in MU_K3]
    rows = [r for rs, _ in runs for r in rs]
    write("stretch_slip_reference.csv", cols, rows,
          [r for mu in MU_K3 for r in run_c(1e-12, mu)[0]], cols)
    for rs, stop in runs:
        for r in rs:
            print(f"mu_k {r['mu_k']} {r['kind']} d {r['d']:.10f}: shift {r['shift']:.10f}, "
                  f"s1 {r['s1']:.9f}, s2 {r['s2']:.9f}, g {r['g']:+d}, "
                  f"|T|/N {abs(r['tangential'] / r['normal']):.7f}, P1 {r['p1']:.4e}, "
                  f"P2 {r['p2']:.4e}, p >= {r['pmin']:.4e}, energy {r['energy']:.10f}, "
                  f"released {r['released']:.4e}, min gap {r['min_gap']:.2e}")
        print(f"mu_k {rs[0]['mu_k']}: stop: {stop}")


if __name__ == "__main__":
    main()
