#!/usr/bin/env python3
"""Independent reference frequencies of the conical (tapered) rod for `vibrissa::modes`
(crates/vibrissa/tests/modes.rs, `tapered_rod_against_reference`).

The straight rod of taper ratio rho (radius r(s) = 1 - a s, a = 1 - rho, solid circular section
of one material): bending stiffness EI(s) = r^4, mass per length rhoA(s) = r^2, normalized at the
foot. Its transverse vibrations w(s) e^{i omega t} (Euler-Bernoulli) satisfy

    (EI w'')'' = omega^2 rhoA w,   w(0) = w'(0) = 0,
    free tip:   EI w''(1) = 0, (EI w'')'(1) = 0
    pinned tip: w(1) = 0,      EI w''(1) = 0

which, multiplied out and divided by r^2, is

    r^2 w'''' - 8 a r w''' + 12 a^2 w'' = omega^2 w.

This is the displacement formulation, not the crate's (x, y, phi, m, G) one, and none of the
crate's code is used: the coefficients are polynomials, so w is its Taylor series about s = 0
(radius 1/a > 1), whose coefficients follow by recurrence in mpmath's arbitrary precision. The
two columns are started by M(0) = EI w''(0) = 1 and by V(0) = (EI w'')'(0) = 1 (with
w(0) = w'(0) = 0); the tip conditions are w''(1) = w'''(1) = 0 (free) or w(1) = w''(1) = 0
(pinned). Their 2x2 determinant is swept in beta = omega^(1/2) with step 0.05 from 0.5 (no mode
is skipped) and each sign change refined by mpmath's `findroot` (Anderson's bracketing method).

Accuracy: each root is solved at 30 digits with 400 terms and at 40 digits with 600 terms; the
script prints the largest relative difference. Values are written with 17 significant digits.

Run from the workspace root: pip install mpmath; python3 data/vibrissa/make_modes_reference.py
(a few seconds)
"""
import mpmath as mp


def det(lam, rho, tip, terms):
    a = 1 - rho
    cols = []
    for c2, c3 in ((mp.mpf(1) / 2, mp.mpf(0)), (mp.mpf(0), mp.mpf(1) / 6)):
        c = [mp.mpf(0), mp.mpf(0), c2, c3]

        def d3(j):
            return (j + 1) * (j + 2) * (j + 3) * c[j + 3] if j >= 0 else 0

        d4 = []  # D4(k) = (k+1)(k+2)(k+3)(k+4) c_{k+4}
        for k in range(terms):
            d2 = (k + 1) * (k + 2) * c[k + 2]
            v = lam * c[k] + 8 * a * (d3(k) - a * d3(k - 1)) - 12 * a * a * d2
            if k >= 1:
                v += 2 * a * d4[k - 1]
            if k >= 2:
                v -= a * a * d4[k - 2]
            d4.append(v)
            c.append(v / ((k + 1) * (k + 2) * (k + 3) * (k + 4)))
        w = mp.fsum(c)
        w2 = mp.fsum(k * (k - 1) * ck for k, ck in enumerate(c))
        w3 = mp.fsum(k * (k - 1) * (k - 2) * ck for k, ck in enumerate(c))
        cols.append((w, w2, w3))
    if tip == "free":
        rows = [(q[1], q[2]) for q in cols]
    else:
        rows = [(q[0], q[1]) for q in cols]
    return rows[0][0] * rows[1][1] - rows[0][1] * rows[1][0]


def roots(rho, tip, count, dps, terms):
    mp.mp.dps = dps
    rho = mp.mpf(rho)
    out = []
    beta = mp.mpf("0.5")
    prev = det(beta**4, rho, tip, terms)
    while len(out) < count:
        b2 = beta + mp.mpf("0.05")
        cur = det(b2**4, rho, tip, terms)
        if mp.sign(cur) != mp.sign(prev):
            lam = mp.findroot(
                lambda l: det(l, rho, tip, terms), (beta**4, b2**4), solver="anderson"
            )
            out.append(mp.sqrt(lam))
        beta, prev = b2, cur
    return out


def main():
    rows = []
    worst = 0
    for rho in ("1", "0.7", "0.3"):
        for tip in ("free", "pinned"):
            lo = roots(rho, tip, 3, 30, 400)
            hi = roots(rho, tip, 3, 40, 600)
            for n, (a, b) in enumerate(zip(lo, hi), start=1):
                worst = max(worst, abs(a / b - 1))
                rows.append((rho, tip, n, b))
    print("largest relative difference (30 digits, 400 terms) vs (40, 600):", mp.nstr(worst, 3))
    with open("data/vibrissa/modes_reference.csv", "w") as fh:
        fh.write("taper,tip,n,omega\n")
        for rho, tip, n, w in rows:
            fh.write(f"{rho},{tip},{n},{mp.nstr(w, 17)}\n")
    for r in rows:
        print(r[0], r[1], r[2], mp.nstr(r[3], 17))


if __name__ == "__main__":
    main()
