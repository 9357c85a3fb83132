#!/usr/bin/env python3
"""Independent high-precision reference values for the `elastica` crate.

Every number is computed from the paper's *integrals* (eqs. 2.7, 2.8, 2.10, 2.15-2.17 of
seed/vibrissa-stiction-paper.md) by direct adaptive tanh-sinh quadrature in mpmath
(`mpmath.quad`, which clusters nodes double-exponentially at the end points and so copes with
the 1/sqrt end-point singularity of [sin(t-a) - sin(phi1-a)]^(-1/2)).  The elliptic-integral
reduction used by the Rust crate is NOT used for the output; it is only evaluated at the end as
a consistency check (`closed_form_*`), and the script aborts if the two disagree.

Run:  python3 data/elastica/make_reference.py   (needs mpmath; CI does not run it)
Writes data/elastica/reference.csv and data/elastica/special_values.csv.
"""
import csv
import math
import os
import sys

import mpmath as mp
from mpmath import mpf, sin, cos, sqrt, pi, asin

DPS = 40
mp.mp.dps = DPS
HERE = os.path.dirname(os.path.abspath(__file__))


# ----------------------------------------------------------------------------------------
# Quadrature of the paper's integrals
# ----------------------------------------------------------------------------------------
def quad(fun, lo, hi):
    """Integral of a smooth integrand over [lo, hi] by tanh-sinh, with its error estimate
    checked (abort if the estimate is not far below the digits we print)."""
    if hi == lo:
        return mpf(0)
    val, err = mp.quad(fun, [lo, hi], error=True, maxdegree=12)
    if err > mpf(10) ** (-(DPS - 15)) * max(1, abs(val)):
        raise RuntimeError(f"quadrature error estimate too large: {err} on [{lo},{hi}]")
    return val


def I_w(phi_lo, phi_hi, phi1, a, weight):
    """int_{phi_lo}^{phi_hi} weight(t) [sin(t-a) - sin(phi1-a)]^(-1/2) dt, for
    phi1 <= phi_lo <= phi_hi <= phib = pi + 2a - phi1 (the two zeros of the bracket).

    The bracket factorises exactly as 2 sin((t-phi1)/2) sin((phib-t)/2).  The trigonometric
    substitution t = phi1 + L sin^2(psi), L = phib - phi1, turns both end-point zeros into
    smooth behaviour:  dt / sqrt(bracket) = 2 L sin(psi) cos(psi) dpsi /
    sqrt(2 sin(L sin^2(psi)/2) sin(L cos^2(psi)/2)), a bounded, analytic integrand.  This is
    elementary calculus, not the elliptic reduction, and it keeps quadrature accurate also when
    phi_hi is within 1e-8 of the far zero phib (near the turning point)."""
    phib = pi + 2 * a - phi1
    L = phib - phi1

    def psi_of(t):
        r = (t - phi1) / L
        r = min(max(r, mpf(0)), mpf(1))
        return asin(sqrt(r))

    def integrand(psi):
        sp, cp = sin(psi), cos(psi)
        t = phi1 + L * sp * sp
        den = sqrt(2 * sin(L * sp * sp / 2) * sin(L * cp * cp / 2))
        return weight(t) * 2 * L * sp * cp / den

    return quad(integrand, psi_of(phi_lo), psi_of(phi_hi))


one = lambda t: mpf(1)


def big_k(phi, phi1, a):
    """Paper (2.7): K(phi, phi1, a) = -int_{pi/2}^{phi} [..]^(-1/2) dt."""
    if phi <= pi / 2:
        return I_w(phi, pi / 2, phi1, a, one)
    return -I_w(pi / 2, phi, phi1, a, one)


def big_xy_unscaled(phi, phi1, a):
    """-int_{pi/2}^{phi} (cos t, sin t) [..]^(-1/2) dt  = sqrt(2f) * (X, Y) of (2.10)."""
    if phi <= pi / 2:
        return (I_w(phi, pi / 2, phi1, a, cos), I_w(phi, pi / 2, phi1, a, sin))
    return (-I_w(pi / 2, phi, phi1, a, cos), -I_w(pi / 2, phi, phi1, a, sin))


def convex(a, phi1):
    """Convex elastica: (f, x1, y1, m_base) from (2.8), (2.10); m_base = m(0) = kappa(0)."""
    k1 = big_k(phi1, phi1, a)
    f = k1 ** 2 / 2
    xs, ys = big_xy_unscaled(phi1, phi1, a)
    x1, y1 = xs / sqrt(2 * f), ys / sqrt(2 * f)
    m_base = f * (-x1 * cos(a) - y1 * sin(a))  # paper's moment formula at s = 0
    return f, x1, y1, m_base


def flex(a, phi1):
    """One-flex elastica: (f, x1, y1, m_base, s_b, phi_b) from (2.12), (2.15)-(2.17)."""
    phib = pi + 2 * a - phi1
    k1 = big_k(phi1, phi1, a)
    kb = big_k(phib, phi1, a)
    f = (k1 - 2 * kb) ** 2 / 2
    g = sqrt(2 * f)
    s_b = -kb / g
    x1s, y1s = big_xy_unscaled(phi1, phi1, a)
    xbs, ybs = big_xy_unscaled(phib, phi1, a)
    x1 = (x1s - 2 * xbs) / g
    y1 = (y1s - 2 * ybs) / g
    m_base = f * (-x1 * cos(a) - y1 * sin(a))
    return f, x1, y1, m_base, s_b, phib


# ----------------------------------------------------------------------------------------
# Closed forms (only as a consistency check of the quadrature; same formulas as the crate)
# ----------------------------------------------------------------------------------------
def closed_form(a, phi1, branch):
    u = phi1 - a
    k = sin((pi / 2 - u) / 2)
    m = k * k
    # theta_top = asin(sin(-a/2)/k), via atan2 with cos^2 written as a product of sines so it
    # keeps full precision at the turning point (delta -> 0)
    delta = pi / 2 + 2 * a - phi1
    c2 = sin(delta / 2) * sin((pi / 2 - phi1) / 2)
    th = mp.atan2(sin(-a / 2), sqrt(c2)) if k != 0 else mpf(0)
    F, E, K, EE = mp.ellipf(th, m), mp.ellipe(th, m), mp.ellipk(m), mp.ellipe(m)
    if branch == "convex":
        g = K + F
        A = 2 * (E + EE) / g - 1
        B = 2 * k * cos(th) / g
        mb = -2 * g * k * cos(th)
    else:
        g = 3 * K - F
        A = 2 * (3 * EE - E) / g - 1
        B = -2 * k * cos(th) / g
        mb = 2 * g * k * cos(th)
    x1 = -A * sin(a) + B * cos(a)
    y1 = A * cos(a) + B * sin(a)
    return g * g, x1, y1, mb


def row(branch, a, phi1):
    """One reference row at the exact double inputs (a, phi1), checked against the closed form."""
    am, pm = mpf(a), mpf(phi1)
    if branch == "convex":
        f, x1, y1, mb = convex(am, pm)
        s_b = mpf("nan")
    else:
        f, x1, y1, mb, s_b, _ = flex(am, pm)
    check(f"{branch} a={a} phi1={phi1}", (f, x1, y1, mb), closed_form(am, pm, branch),
          mpf(10) ** -28)
    return (branch, a, phi1, f, x1, y1, mb, s_b)


def check(name, q, c, tol):
    for qq, cc in zip(q, c):
        if abs(qq - cc) > tol * max(1, abs(cc)):
            raise RuntimeError(f"{name}: quadrature {qq} vs closed form {cc}")


def s20(v):
    return mp.nstr(v, 20, min_fixed=-5, max_fixed=5, strip_zeros=False)


# ----------------------------------------------------------------------------------------
def main():
    rows = []
    # Inputs are IEEE doubles (exactly representable, printed with repr so that Rust parses the
    # very same f64): near the turning point f is a square-root function of the distance
    # delta = pi/2 + 2a - phi1, so the reference must be computed at the exact f64 inputs.
    # alpha grid: both ends and the interior; phi1 as a fraction of the admissible range
    # [0, pi/2 + 2a], including values very close to both ends (1e-8 and 1 - 1e-6, and the end
    # itself: the largest double <= pi/2 + 2a).
    alphas = [0.0, -1e-6, -0.05, float(-pi / 8), -0.5, -0.7, float(-pi / 4 + mpf("1e-6"))]
    fracs = ["0", "1e-8", "0.25", "0.5", "0.9", "0.999999", "1"]
    for branch in ("convex", "flex"):
        for a in alphas:
            for fr in fracs:
                top = pi / 2 + 2 * mpf(a)
                phi1 = float(top * mpf(fr))
                while mpf(phi1) > top:
                    phi1 = math.nextafter(phi1, 0.0)
                if a == 0.0 and fr == "1":
                    # phi1 = pi/2 at alpha = 0: the straight rod at a buckling load (k = 0);
                    # take the closest double below pi/2 instead (a k ~ 1e-8 elastica).
                    pass
                rows.append(row(branch, a, phi1))
        # the single admissible point at alpha = -pi/4 (phi1 = 0 = pi/2 + 2a up to rounding:
        # float(-pi/4) > -pi/4, so phi1 = 0 is admissible)
        rows.append(row(branch, float(-pi / 4), 0.0))

    with open(os.path.join(HERE, "reference.csv"), "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(["branch", "alpha", "phi1", "f", "x1", "y1", "m_base", "s_b"])
        for r in rows:
            w.writerow([r[0], repr(r[1]), repr(r[2])]
                       + [("nan" if mp.isnan(v) else s20(v)) for v in r[3:]])
    print(f"reference.csv: {len(rows)} rows", file=sys.stderr)

    # ---------------- special values ----------------
    special = []
    # section 3.1: f_ = 1/2 K^2(0,0,0), eta_ = Y(0; f_, 0, 0)
    f_, x_, eta_, _ = convex(mpf(0), mpf(0))
    special += [("f_lower", "", "", f_, "section 3.1, printed 3.4373"),
                ("eta_lower", "", "", eta_, "section 3.1, printed 0.4569"),
                ("x1_lower", "", "", x_, "tip x of that rod")]
    # turning points f_a = 4 K^2(sin(a/2)) (modulus form: m = sin^2(a/2)) vs quadrature
    for a in [mpf("-0.01"), mpf("-0.1"), -pi / 8, mpf("-0.5"), -pi / 4]:
        fa = 4 * mp.ellipk(sin(a / 2) ** 2) ** 2
        fq = convex(a, pi / 2 + 2 * a)[0]
        # phi1 = pi/2 + 2a is rounded at dps 40; f is a sqrt function of the distance to the
        # turning point, so agreement is limited to ~sqrt(1e-40) = 1e-20 here
        if abs(fa - fq) > mpf(10) ** -18 * fa:
            raise RuntimeError("turning point formula")
        special.append(("turning_f", s20(a), s20(pi / 2 + 2 * a), fq, "4 K^2(sin(a/2))"))
    # Fig. 3: a = -pi/8, phi1 = (pi/2 + 2a)/2
    a = -pi / 8
    p = (pi / 2 + 2 * a) / 2
    special.append(("fig3_f_convex", s20(a), s20(p), convex(a, p)[0], "printed 4.72"))
    special.append(("fig3_f_flex", s20(a), s20(p), flex(a, p)[0], "printed 19.0"))
    # buckling limits
    special.append(("buckling_1", "0", s20(pi / 2), pi ** 2 / 4, "pi^2/4"))
    special.append(("buckling_2", "0", s20(pi / 2), 9 * pi ** 2 / 4, "9 pi^2/4"))

    # scan start (alpha = 0, convex, y1 = eta) and turning point alpha_t (phi1 = pi/2 + 2a)
    for eta in [mpf("0.6"), mpf("0.75")]:
        p0 = mp.findroot(lambda p: convex(mpf(0), p)[2] - eta, (mpf("0.2"), mpf("1.3")),
                         solver="anderson")
        f0, x0, _, _ = convex(mpf(0), p0)
        special.append(("scan_start_phi1", "0", s20(eta), p0, f"eta={eta}"))
        special.append(("scan_start_f", "0", s20(eta), f0, f"eta={eta}"))
        special.append(("scan_start_x1", "0", s20(eta), x0, f"eta={eta}"))
        yt = lambda a: convex(a, pi / 2 + 2 * a)[2] - eta
        lo, hi = -pi / 4, mpf("-1e-3")
        if yt(lo) * yt(hi) < 0:
            at = mp.findroot(yt, (lo, hi), solver="anderson")
            special.append(("turning_alpha", s20(at), s20(eta), at, f"eta={eta}"))
            special.append(("turning_phi1", s20(at), s20(eta), pi / 2 + 2 * at, f"eta={eta}"))
            special.append(("turning_f_eta", s20(at), s20(eta), convex(at, pi / 2 + 2 * at)[0],
                            f"eta={eta}"))
        else:
            special.append(("turning_alpha", "", s20(eta), mpf("nan"),
                            f"eta={eta}: no turning point in [-pi/4, 0]; y1 at (-pi/4, 0) = "
                            + s20(convex(-pi / 4, mpf(0))[2])))
    special.append(("y1_turning_at_minus_pi_4", s20(-pi / 4), "0", convex(-pi / 4, mpf(0))[2],
                    "tip height of the turning-point rod at alpha=-pi/4, phi1=0"))

    with open(os.path.join(HERE, "special_values.csv"), "w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(["name", "alpha", "param", "value", "note"])
        for name, a, p, v, note in special:
            w.writerow([name, a, p, ("nan" if mp.isnan(v) else s20(v)), note])
    print(f"special_values.csv: {len(special)} rows (mpmath {mp.__version__}, dps {DPS})",
          file=sys.stderr)


if __name__ == "__main__":
    main()
