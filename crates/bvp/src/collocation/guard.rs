//! The guard of residual control: a cheap estimate of the true error of a solution that met the
//! residual tolerance, by deferred correction with the factored Newton matrix.
//!
//! The discrete solution `u_h` solves `R_h(u_h) = 0` (the scheme). Let `R_H` be a discretization
//! of higher order on the same nodes: row `i` is `(z_{i+1} − z_i)/h_i − (1/h_i) ∫ F(s, P(s)) ds`
//! over interval `i`, with `P` the two-point Hermite interpolant of the nodal values and their
//! derivatives `z' = F`, `z''`, (Lobatto6) `z'''` (differences of `F` along the solution from
//! inside the interval): quintic for Lobatto4 (`R_H` of order 6 against 4), septic for Lobatto6
//! (order 8 against 6). Its truncation error on the exact solution is of higher order, so
//! `R_H(u_h) ≈ J (u_h − y)` and the nodal error is `e ≈ J⁻¹ R_H(u_h)`: one solve with the
//! factored Newton matrix `J` (node rows `R_H(u_h)`, stage rows 0 — Lobatto6's stages are then
//! eliminated as in the nodal one-step scheme —, boundary rows `g(u_h)`). Since
//! `∫ P' = z_{i+1} − z_i`, row `i` of `R_H(u_h)` is the integral of `P`'s residual
//! `P' − F(s, P)`, which vanishes at the nodes: 5-point Lobatto quadrature, three evaluations of
//! `F` per interval. The estimate is asymptotically correct (relative `O(h²)`), not a bound; it
//! sees the error that residual control does not, the residual propagated by an ill-conditioned
//! problem (a periodic epidemic model at tol 1e-4: residual 8.5e-5, error 5.2e-3).
//!
//! The error of the returned interpolant `S` between nodes adds `|S − P|` (the interpolant's own
//! error against the more accurate `P`): per interval, `max (max(|e_i|, |e_{i+1}|) + |S − P|) /
//! (1 + |S|)` componentwise over the ends and the three interior points.
//!
//! Cost per accepted mesh: 7 (Lobatto4) or 9 (Lobatto6) evaluations of `F` per interval, one bc
//! evaluation and one back-substitution (a factorization if Newton accepted without one here).

use super::{Disc, EST_T, EST_W};
use crate::{Bvp, Solution, Stats};

/// Most data per end of a Hermite interpolant here (value and three derivatives).
const MAXM: usize = 4;

/// Values and `t`-derivatives at `t` of the basis of the two-point Hermite interpolant on
/// `[0, 1]` of degree `2m − 1`: data ordered `p(0), p'(0), …, p^(m−1)(0), p(1), …, p^(m−1)(1)`.
fn hermite_basis(m: usize, t: f64) -> ([f64; 2 * MAXM], [f64; 2 * MAXM]) {
    let d = 2 * m;
    // a[row][j]: the row's functional (derivative `k` at `x`) applied to t^j.
    let mut a = [[0.0; 2 * MAXM]; 2 * MAXM];
    for (row, ar) in a.iter_mut().enumerate().take(d) {
        let (x, k) = if row < m {
            (0.0_f64, row)
        } else {
            (1.0, row - m)
        };
        for (j, v) in ar.iter_mut().enumerate().take(d).skip(k) {
            let falling: f64 = (j - k + 1..=j).map(|f| f as f64).product();
            *v = falling * x.powi((j - k) as i32);
        }
    }
    // Basis k has coefficients column k of a⁻¹: Gauss–Jordan on [a | I].
    let mut inv = [[0.0; 2 * MAXM]; 2 * MAXM];
    for (i, r) in inv.iter_mut().enumerate().take(d) {
        r[i] = 1.0;
    }
    for col in 0..d {
        let piv = (col..d)
            .max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))
            .unwrap_or(col);
        a.swap(col, piv);
        inv.swap(col, piv);
        let p = a[col][col];
        for j in 0..d {
            a[col][j] /= p;
            inv[col][j] /= p;
        }
        for r in 0..d {
            if r != col && a[r][col] != 0.0 {
                let f = a[r][col];
                for j in 0..d {
                    a[r][j] -= f * a[col][j];
                    inv[r][j] -= f * inv[col][j];
                }
            }
        }
    }
    let (mut val, mut der) = ([0.0; 2 * MAXM], [0.0; 2 * MAXM]);
    for k in 0..d {
        for j in 0..d {
            val[k] += inv[j][k] * t.powi(j as i32);
            if j > 0 {
                der[k] += inv[j][k] * j as f64 * t.powi(j as i32 - 1);
            }
        }
    }
    (val, der)
}

impl<P: Bvp + ?Sized> Disc<'_, P> {
    /// `z''' = d²/ds² F(s, z(s), p)` at both ends of every interval (layout of `d2z`), each from
    /// inside its interval: along the curve `z + σδ F + δ²/2 z''` (which follows the solution to
    /// `O(δ³)`), `g(δ) = F(s + σδ, ·)` has `g''(0) = z'''`; the one-sided difference
    /// `(2g(0) − 5g(δ) + 4g(2δ) − g(3δ)) / δ²`, `δ = ε^¼ h`, has a relative error `O(√ε)`.
    fn third_derivatives(
        &mut self,
        p: &[f64],
        (z, dz, d2z): (&[f64], &[f64], &[f64]),
        stats: &mut Stats,
    ) -> Vec<f64> {
        let n = self.lay.n;
        let m = self.mesh;
        let mut d3 = vec![0.0; d2z.len()];
        let mut g = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        for i in 0..m.len() - 1 {
            let d = f64::EPSILON.sqrt().sqrt() * (m[i + 1] - m[i]);
            for (end, node, sign) in [(0, i, 1.0), (1, i + 1, -1.0)] {
                let (zi, fi) = (&z[node * n..(node + 1) * n], &dz[node * n..(node + 1) * n]);
                let sec = &d2z[(2 * i + end) * n..(2 * i + end + 1) * n];
                for (k, gk) in g.iter_mut().enumerate() {
                    let step = (k + 1) as f64 * d;
                    let tmp = &mut self.w.tmp;
                    for c in 0..n {
                        tmp[c] = zi[c] + sign * step * fi[c] + 0.5 * step * step * sec[c];
                    }
                    self.prob.rhs(m[node] + sign * step, tmp, p, gk);
                }
                stats.rhs_evals += 3;
                let out = &mut d3[(2 * i + end) * n..(2 * i + end + 1) * n];
                for c in 0..n {
                    let v = (2.0 * fi[c] - 5.0 * g[0][c] + 4.0 * g[1][c] - g[2][c]) / (d * d);
                    out[c] = if v.is_finite() { v } else { 0.0 };
                }
            }
        }
        d3
    }

    /// The guard's estimate (module docs) of the error of `sol`, the returned object of the
    /// discrete solution `u` on this mesh (points current), with `d2z` the one-sided `z''` of
    /// [`crate::Dense::QuinticIntervals`] at the ends of every interval (Lobatto6; computed here
    /// for Lobatto4). Errors relative to `1 + |S_c|` pointwise, or with `scale` to
    /// `1 + scale[c]` ([`super::run::scales`]). `None` if it cannot be formed (NaN/∞ of `F`, a
    /// singular matrix).
    pub(super) fn guard(
        &mut self,
        u: &[f64],
        sol: &Solution,
        (d2z, scale): (Option<&[f64]>, Option<&[f64]>),
        stats: &mut Stats,
    ) -> Option<f64> {
        let (n, stride) = (self.lay.n, self.lay.stride);
        let p = &sol.params;
        let own;
        let d2z = match d2z {
            Some(d) => d,
            None => {
                own = self.second_derivatives(p, &sol.z, &sol.dz, stats);
                &own
            }
        };
        let d3z = self
            .tab
            .internal
            .then(|| self.third_derivatives(p, (&sol.z, &sol.dz, d2z), stats));
        let m = if d3z.is_some() { 4 } else { 3 };
        let (rhs, gap) = self.hermite_defects(sol, (m, d2z, d3z.as_deref()), scale, stats)?;
        let mut x = vec![0.0; self.lay.dim()];
        for i in 0..self.lay.intervals() {
            let row = i * stride + stride - n;
            x[row..row + n].copy_from_slice(&rhs[i * n..(i + 1) * n]);
        }
        self.ensure_points(u, stats).ok()?;
        self.bc_residual(u, stats);
        if !self.factored {
            self.linearize(u, stats).ok()?;
        }
        let b = self.lay.bcrow();
        let nb = x.len() - b;
        x[b..].copy_from_slice(&self.w.g[..nb]);
        self.w.sys.solve(&mut x).ok()?;
        let mut worst = 0.0_f64;
        for i in 0..self.lay.intervals() {
            for c in 0..n {
                let size = |node: usize| scale.map_or(sol.z[node * n + c].abs(), |s| s[c]);
                let rel = |node: usize| x[node * stride + c].abs() / (1.0 + size(node));
                worst = worst.max(rel(i).max(rel(i + 1)) + gap[i * n + c]);
            }
        }
        worst.is_finite().then_some(worst)
    }

    /// Per interval: the integral of the Hermite interpolant's residual `(1/h) ∫ (P' − F(s, P))`
    /// (`n` values, the node row of `R_H(u_h)`) and `max |S − P| / (1 + |S|)` at the interior
    /// points (`n` values; with `scale`, `|S − P| / (1 + scale[c])`), `S` the returned object.
    /// `m` data per end: value, `F`, `d2z`, `d3z`.
    fn hermite_defects(
        &mut self,
        sol: &Solution,
        (m, d2z, d3z): (usize, &[f64], Option<&[f64]>),
        scale: Option<&[f64]>,
        stats: &mut Stats,
    ) -> Option<(Vec<f64>, Vec<f64>)> {
        let n = self.lay.n;
        let nint = self.lay.intervals();
        let basis: Vec<_> = EST_T.iter().map(|&t| hermite_basis(m, t)).collect();
        let (mut rhs, mut gap) = (vec![0.0_f64; nint * n], vec![0.0_f64; nint * n]);
        let (mut pv, mut pd, mut f, mut sv) =
            (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        for i in 0..nint {
            let (s0, h) = (self.mesh[i], self.mesh[i + 1] - self.mesh[i]);
            for (e, (val, der)) in basis.iter().enumerate() {
                for c in 0..n {
                    let mut data = [0.0; 2 * MAXM];
                    for (end, node) in [(0, i), (1, i + 1)] {
                        let at = |v: &[f64], k: usize| v[k * n + c];
                        let o = end * m;
                        data[o] = at(&sol.z, node);
                        data[o + 1] = h * at(&sol.dz, node);
                        data[o + 2] = h * h * at(d2z, 2 * i + end);
                        if let Some(d3) = d3z {
                            data[o + 3] = h * h * h * at(d3, 2 * i + end);
                        }
                    }
                    pv[c] = (0..2 * m).map(|k| val[k] * data[k]).sum();
                    pd[c] = (0..2 * m).map(|k| der[k] * data[k]).sum::<f64>() / h;
                }
                let s = s0 + EST_T[e] * h;
                self.prob.rhs(s, &pv, &sol.params, &mut f);
                stats.rhs_evals += 1;
                sol.eval(s, &mut sv);
                for c in 0..n {
                    rhs[i * n + c] += EST_W[e] * (pd[c] - f[c]);
                    let size = scale.map_or(sv[c].abs(), |s| s[c]);
                    let g = (sv[c] - pv[c]).abs() / (1.0 + size);
                    gap[i * n + c] = gap[i * n + c].max(g);
                }
            }
        }
        rhs.iter().all(|v| v.is_finite()).then_some((rhs, gap))
    }
}

#[cfg(test)]
mod tests {
    use super::hermite_basis;

    /// The basis reproduces polynomials of its degree: data of `t^j` give `t^j` and `j t^(j−1)`.
    #[test]
    fn hermite_basis_reproduces_its_degree() {
        for m in [3, 4] {
            for j in 0..2 * m {
                let jf = j as f64;
                let mut data = [0.0; 8];
                for k in 0..m.min(j + 1) {
                    // d^k/dt^k t^j = j!/(j−k)! t^(j−k): at 0 only for k = j, at 1 always.
                    let falling: f64 = (j - k + 1..=j).map(|f| f as f64).product();
                    data[k] = if k == j { falling } else { 0.0 };
                    data[m + k] = falling;
                }
                for t in [0.1, 0.5, 0.83] {
                    let (v, d) = hermite_basis(m, t);
                    let pv: f64 = (0..2 * m).map(|k| v[k] * data[k]).sum();
                    let pd: f64 = (0..2 * m).map(|k| d[k] * data[k]).sum();
                    assert!((pv - t.powi(j as i32)).abs() < 1e-12, "m {m} j {j} t {t}");
                    let exact = if j == 0 {
                        0.0
                    } else {
                        jf * t.powi(j as i32 - 1)
                    };
                    assert!((pd - exact).abs() < 1e-11, "m {m} j {j} t {t}: {pd}");
                }
            }
        }
    }
}
