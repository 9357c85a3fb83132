//! Lobatto IIIA tableaux and the continuous extension of the collocation polynomial.
//!
//! Everything is derived from the abscissae `c` by Lagrange interpolation, so the coefficients are
//! exact to rounding by construction: `a[r][j] = ∫_0^{c_r} L_j`, where `L_j` is the Lagrange basis on `c`.

use super::Scheme;

/// Most abscissae of a supported scheme (4-point Lobatto).
pub(crate) const MAXC: usize = 4;

pub(crate) use crate::solution::{EST_T, EST_W};

/// A Lobatto IIIA scheme on the unit interval.
#[derive(Clone, Debug)]
pub(crate) struct Tableau {
    /// Number of abscissae minus one (points per interval besides the left node).
    pub q: usize,
    /// Abscissae `c_0 = 0 < … < c_q = 1`.
    pub c: [f64; MAXC],
    /// `a[r][j] = ∫_0^{c_r} L_j`.
    pub a: [[f64; MAXC]; MAXC],
    /// Internal stages are unknowns of the global system (6th order); otherwise the midpoint is
    /// eliminated explicitly by the Hermite formula (4th order).
    pub internal: bool,
    /// Lagrange polynomial coefficients, `lc[j][m]` multiplies `t^m`.
    lc: [[f64; MAXC]; MAXC],
}

impl Tableau {
    pub(crate) fn new(scheme: Scheme) -> Self {
        let (q, c, internal) = match scheme {
            Scheme::Lobatto4 => (2, [0.0, 0.5, 1.0, 0.0], false),
            Scheme::Lobatto6 => {
                let r5 = 5f64.sqrt();
                (3, [0.0, (5.0 - r5) / 10.0, (5.0 + r5) / 10.0, 1.0], true)
            }
        };
        let m = q + 1;
        let mut lc = [[0.0; MAXC]; MAXC];
        for (j, lcj) in lc.iter_mut().enumerate().take(m) {
            // Multiply out prod_{i != j} (t - c_i) / (c_j - c_i).
            let mut poly = [0.0; MAXC];
            poly[0] = 1.0;
            let mut deg = 0;
            for i in 0..m {
                if i == j {
                    continue;
                }
                let d = c[j] - c[i];
                let mut next = [0.0; MAXC];
                for e in 0..=deg {
                    next[e + 1] += poly[e] / d;
                    next[e] -= poly[e] * c[i] / d;
                }
                poly = next;
                deg += 1;
            }
            *lcj = poly;
        }
        let mut t = Tableau {
            q,
            c,
            a: [[0.0; MAXC]; MAXC],
            internal,
            lc,
        };
        for r in 0..m {
            let mut row = [0.0; MAXC];
            t.weights(c[r], &mut row, &mut [0.0; MAXC]);
            t.a[r] = row;
        }
        t
    }

    /// Number of abscissae.
    pub(crate) fn m(&self) -> usize {
        self.q + 1
    }

    /// Weights of the collocation polynomial at `t ∈ [0, 1]`:
    /// `S(t) = y_0 + h Σ_j int[j] f_j`, `S'(t) = Σ_j der[j] f_j`.
    pub(crate) fn weights(&self, t: f64, int: &mut [f64; MAXC], der: &mut [f64; MAXC]) {
        for j in 0..self.m() {
            let (mut vi, mut vd, mut tp) = (0.0, 0.0, 1.0);
            for e in 0..self.m() {
                vd += self.lc[j][e] * tp;
                tp *= t;
                vi += self.lc[j][e] * tp / (e + 1) as f64;
            }
            int[j] = vi;
            der[j] = vd;
        }
    }

    /// Weights of the second derivative of the collocation polynomial at `t ∈ [0, 1]`:
    /// `S''(t) = Σ_j sec[j] f_j / h`.
    pub(crate) fn second(&self, t: f64, sec: &mut [f64; MAXC]) {
        for (j, out) in sec.iter_mut().enumerate().take(self.m()) {
            let (mut v, mut tp) = (0.0, 1.0);
            for e in 1..self.m() {
                v += e as f64 * self.lc[j][e] * tp;
                tp *= t;
            }
            *out = v;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lobatto4_is_simpson_and_hermite() {
        let t = Tableau::new(Scheme::Lobatto4);
        let b = t.a[2];
        assert!((b[0] - 1.0 / 6.0).abs() < 1e-15 && (b[1] - 4.0 / 6.0).abs() < 1e-15);
        // Midpoint row of Lobatto IIIA(3): 5/24, 1/3, -1/24.
        assert!((t.a[1][0] - 5.0 / 24.0).abs() < 1e-15);
        assert!((t.a[1][1] - 1.0 / 3.0).abs() < 1e-15);
        assert!((t.a[1][2] + 1.0 / 24.0).abs() < 1e-15);
    }

    #[test]
    fn lobatto6_matches_published_tableau() {
        // Hairer & Wanner, Solving ODEs II, Table IV.5.7 (Lobatto IIIA, s = 4).
        let t = Tableau::new(Scheme::Lobatto6);
        let r5 = 5f64.sqrt();
        let want = [
            [
                (11.0 + r5) / 120.0,
                (25.0 - r5) / 120.0,
                (25.0 - 13.0 * r5) / 120.0,
                (-1.0 + r5) / 120.0,
            ],
            [
                (11.0 - r5) / 120.0,
                (25.0 + 13.0 * r5) / 120.0,
                (25.0 + r5) / 120.0,
                (-1.0 - r5) / 120.0,
            ],
            [1.0 / 12.0, 5.0 / 12.0, 5.0 / 12.0, 1.0 / 12.0],
        ];
        for r in 0..3 {
            for j in 0..4 {
                assert!(
                    (t.a[r + 1][j] - want[r][j]).abs() < 1e-14,
                    "a[{}][{j}]",
                    r + 1
                );
            }
        }
    }

    #[test]
    fn second_derivative_weights_differentiate_the_polynomial() {
        for scheme in [Scheme::Lobatto4, Scheme::Lobatto6] {
            let t = Tableau::new(scheme);
            // f_j = values of a cubic at the abscissae: S' is that cubic, S'' its derivative.
            let g = |x: f64| 1.0 - 2.0 * x + 3.0 * x * x - 0.5 * x * x * x;
            let dg = |x: f64| -2.0 + 6.0 * x - 1.5 * x * x;
            let f: Vec<f64> = (0..t.m()).map(|j| g(t.c[j])).collect();
            for x in [0.0, 0.3, 1.0] {
                let mut sec = [0.0; MAXC];
                t.second(x, &mut sec);
                let v: f64 = (0..t.m()).map(|j| sec[j] * f[j]).sum();
                let want = if t.m() == 4 {
                    dg(x)
                } else {
                    // Lobatto4: S' is the quadratic through the three values.
                    let (a, b, c) = (f[0], f[1], f[2]);
                    (-3.0 * a + 4.0 * b - c) * (1.0 - x) + (a - 4.0 * b + 3.0 * c) * x
                };
                assert!((v - want).abs() < 1e-12, "{scheme:?} t {x}: {v} vs {want}");
            }
        }
    }
}
