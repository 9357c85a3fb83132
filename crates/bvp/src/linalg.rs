//! Small dense linear algebra without allocation: LU with partial pivoting on caller slices.
//!
//! Matrices are row-major `n × n` slices (`a[i * n + j]`). [`lu_factor`] overwrites `a` with the
//! unit-lower factor `L` (below the diagonal) and `U` (on and above), and records the row
//! permutation in `piv` (`piv[k]` = row swapped with row `k` at step `k`, LAPACK style).
//! [`lu_solve`] then solves `A x = b` in place. Cost `⅔ n³` flops for the factorization, `2 n²`
//! per solve; intended for the small systems of single and multiple shooting (`n` up to a few
//! hundred).
//!
//! # Singularity
//!
//! A pivot is declared zero when `|u_kk| ≤ pivot_tol · max_ij |a_ij|` (the largest entry of the
//! *original* matrix), i.e. the threshold is relative, so the test does not depend on the units of
//! the problem. [`DEFAULT_PIVOT_TOL`] (`n`-independent, `1e-14`) flags matrices that are singular
//! to working precision; pass a larger value to also reject badly ill-conditioned ones.
//!
//! [`DenseLu`] owns its buffers and can be reused for many factorizations of the same size
//! without allocating.

/// Default relative pivot threshold of [`lu_factor`]: `1e-14` (about 45 ε).
pub const DEFAULT_PIVOT_TOL: f64 = 1e-14;

/// A zero (or relatively negligible) pivot met during factorization.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SingularMatrix {
    /// Elimination step (column) at which the pivot was negligible.
    pub column: usize,
    /// The best pivot available in that column (absolute value).
    pub pivot: f64,
    /// The threshold it failed: `pivot_tol · max |a_ij|`.
    pub threshold: f64,
}

/// Factorizes the row-major `n × n` matrix `a` in place as `P A = L U` with partial pivoting.
///
/// `piv` must have length `n`. Returns [`SingularMatrix`] when a pivot is at most
/// `pivot_tol · max |a_ij|` (or the matrix contains NaN/∞, or is entirely zero); `a` is then
/// partially overwritten. Never allocates, never panics for consistent slice lengths
/// (`a.len() >= n * n`, `piv.len() >= n`).
pub fn lu_factor(
    a: &mut [f64],
    n: usize,
    piv: &mut [usize],
    pivot_tol: f64,
) -> Result<(), SingularMatrix> {
    let a = &mut a[..n * n];
    let mut amax = 0.0_f64;
    for &x in a.iter() {
        if !x.is_finite() {
            return Err(SingularMatrix {
                column: 0,
                pivot: f64::NAN,
                threshold: f64::NAN,
            });
        }
        amax = amax.max(x.abs());
    }
    let threshold = pivot_tol * amax;
    for k in 0..n {
        // Pivot search in column k.
        let mut p = k;
        let mut best = a[k * n + k].abs();
        for i in k + 1..n {
            let v = a[i * n + k].abs();
            if v > best {
                best = v;
                p = i;
            }
        }
        piv[k] = p;
        if best <= threshold || best == 0.0 {
            return Err(SingularMatrix {
                column: k,
                pivot: best,
                threshold,
            });
        }
        if p != k {
            for j in 0..n {
                a.swap(k * n + j, p * n + j);
            }
        }
        let inv = 1.0 / a[k * n + k];
        let (top, bottom) = a.split_at_mut((k + 1) * n);
        let row_k = &top[k * n..k * n + n];
        for row_i in bottom.chunks_exact_mut(n) {
            let l = row_i[k] * inv;
            row_i[k] = l;
            if l != 0.0 {
                for j in k + 1..n {
                    row_i[j] -= l * row_k[j];
                }
            }
        }
    }
    Ok(())
}

/// Solves `A x = b` in place (`b` becomes `x`) with the factors from [`lu_factor`].
pub fn lu_solve(lu: &[f64], n: usize, piv: &[usize], b: &mut [f64]) {
    let b = &mut b[..n];
    for (k, &p) in piv.iter().enumerate().take(n) {
        if p != k {
            b.swap(k, p);
        }
    }
    // Forward substitution with unit-lower L.
    for i in 1..n {
        let row = &lu[i * n..i * n + i];
        let mut s = b[i];
        for (j, &l) in row.iter().enumerate() {
            s -= l * b[j];
        }
        b[i] = s;
    }
    // Back substitution with U.
    for i in (0..n).rev() {
        let row = &lu[i * n..(i + 1) * n];
        let mut s = b[i];
        for j in i + 1..n {
            s -= row[j] * b[j];
        }
        b[i] = s / row[i];
    }
}

/// Reusable dense LU: owns an `n × n` matrix buffer and the pivots.
///
/// Fill [`DenseLu::matrix_mut`], call [`DenseLu::factor`], then [`DenseLu::solve`] any number of
/// right-hand sides. [`DenseLu::resize`] only allocates when the size grows beyond what was seen.
#[derive(Clone, Debug, Default)]
pub struct DenseLu {
    n: usize,
    a: Vec<f64>,
    piv: Vec<usize>,
    /// Relative pivot threshold (see module docs). Default [`DEFAULT_PIVOT_TOL`].
    pub pivot_tol: f64,
}

impl DenseLu {
    /// A factorization workspace for `n × n` matrices.
    pub fn new(n: usize) -> Self {
        DenseLu {
            n,
            a: vec![0.0; n * n],
            piv: vec![0; n],
            pivot_tol: DEFAULT_PIVOT_TOL,
        }
    }

    /// Changes the size (contents become zero).
    pub fn resize(&mut self, n: usize) {
        self.n = n;
        self.a.clear();
        self.a.resize(n * n, 0.0);
        self.piv.clear();
        self.piv.resize(n, 0);
    }

    /// The size `n`.
    pub fn n(&self) -> usize {
        self.n
    }

    /// The row-major matrix to fill before [`DenseLu::factor`] (overwritten by the factors).
    pub fn matrix_mut(&mut self) -> &mut [f64] {
        &mut self.a
    }

    /// Factorizes the matrix in place.
    pub fn factor(&mut self) -> Result<(), SingularMatrix> {
        lu_factor(&mut self.a, self.n, &mut self.piv, self.pivot_tol)
    }

    /// Solves `A x = b` in place, after a successful [`DenseLu::factor`].
    pub fn solve(&self, b: &mut [f64]) {
        lu_solve(&self.a, self.n, &self.piv, b);
    }
}

/// `y ← A x` for a row-major `m × n` matrix (helper for residual checks and tests).
pub fn matvec(a: &[f64], m: usize, n: usize, x: &[f64], y: &mut [f64]) {
    for i in 0..m {
        let row = &a[i * n..(i + 1) * n];
        y[i] = row.iter().zip(x).map(|(a, b)| a * b).sum();
    }
}

/// Max-norm `max |x_i|` (NaN if any entry is NaN).
pub fn norm_max(x: &[f64]) -> f64 {
    let mut m = 0.0_f64;
    for &v in x {
        if v.is_nan() {
            return f64::NAN;
        }
        m = m.max(v.abs());
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_pivoting_system() {
        // Needs a row swap at the first step (a_00 = 0).
        let a0 = [0.0, 2.0, 1.0, 1.0, 1.0, 1.0, 2.0, 1.0, 3.0];
        let x_true = [1.0, -2.0, 3.0];
        let mut b = [0.0; 3];
        matvec(&a0, 3, 3, &x_true, &mut b);
        let mut a = a0;
        let mut piv = [0; 3];
        lu_factor(&mut a, 3, &mut piv, DEFAULT_PIVOT_TOL).unwrap();
        lu_solve(&a, 3, &piv, &mut b);
        for i in 0..3 {
            assert!((b[i] - x_true[i]).abs() < 1e-14, "{b:?}");
        }
    }

    #[test]
    fn hilbert_residual_small() {
        let n = 8;
        let mut lu = DenseLu::new(n);
        let mut h = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                h[i * n + j] = 1.0 / (i + j + 1) as f64;
            }
        }
        lu.matrix_mut().copy_from_slice(&h);
        lu.factor().unwrap();
        let b: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut x = b.clone();
        lu.solve(&mut x);
        let mut r = vec![0.0; n];
        matvec(&h, n, n, &x, &mut r);
        let res: f64 = r
            .iter()
            .zip(&b)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        // Backward stable: residual ~ ε |H| |x|.
        assert!(res < 1e-12 * norm_max(&x).max(1.0), "residual {res}");
    }

    #[test]
    fn detects_singular_and_nan() {
        let mut a = [1.0, 2.0, 2.0, 4.0];
        let mut piv = [0; 2];
        let e = lu_factor(&mut a, 2, &mut piv, DEFAULT_PIVOT_TOL).unwrap_err();
        assert_eq!(e.column, 1);
        let mut a = [1.0, f64::NAN, 2.0, 4.0];
        assert!(lu_factor(&mut a, 2, &mut piv, DEFAULT_PIVOT_TOL).is_err());
        let mut a = [0.0; 4];
        assert!(lu_factor(&mut a, 2, &mut piv, DEFAULT_PIVOT_TOL).is_err());
        // Relative threshold: scaling the matrix does not change the verdict.
        let mut a = [1e-300, 0.0, 0.0, 2e-300];
        assert!(lu_factor(&mut a, 2, &mut piv, DEFAULT_PIVOT_TOL).is_ok());
    }
}
