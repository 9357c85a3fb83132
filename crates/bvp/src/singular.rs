//! The singular term `S z / s` of [`Bvp::singular_term`], as an ordinary problem for the solvers.

use crate::linalg::DenseLu;
use crate::{Bvp, BvpError, Dims};
use std::cell::RefCell;

/// `z' = S z / s + F(s, z, p)` with `z'(0) = D F(0, z, p)`, `D = (I − S)⁻¹`: the problem the
/// solvers discretize when [`Bvp::singular_term`] is set (it reports no singular term itself).
pub(crate) struct Regular<'a, P: ?Sized> {
    inner: &'a P,
    s: Vec<f64>,
    d: Vec<f64>,
    n: usize,
    buf: RefCell<Vec<f64>>,
}

/// Offset of the series start of shooting from `s = 0`, relative to the interval length.
pub(crate) const SERIES_START: f64 = 1e-7;

impl<'a, P: Bvp + ?Sized> Regular<'a, P> {
    /// The regularized problem, or `None` if `inner` has no singular term.
    pub fn new(inner: &'a P) -> Result<Option<Self>, BvpError> {
        let Some(s) = inner.singular_term() else {
            return Ok(None);
        };
        let Dims { n, .. } = inner.dims();
        let invalid = |value: String, reason| BvpError::InvalidOption {
            name: "singular_term",
            value,
            reason,
        };
        if s.len() != n * n || !s.iter().all(|v| v.is_finite()) {
            return Err(invalid(
                format!("{} values", s.len()),
                "must be n × n finite values",
            ));
        }
        let (a, _) = inner.interval();
        if a != 0.0 {
            return Err(invalid(
                format!("interval starting at {a}"),
                "a singular term S z / s needs the interval to start at 0",
            ));
        }
        let mut lu = DenseLu::new(n);
        for (i, m) in lu.matrix_mut().iter_mut().enumerate() {
            *m = f64::from(u8::from(i / n == i % n)) - s[i];
        }
        lu.factor()
            .map_err(|_| invalid(format!("{s:?}"), "I − S must be invertible"))?;
        let mut d = vec![0.0; n * n];
        let mut col = vec![0.0; n];
        for j in 0..n {
            col.fill(0.0);
            col[j] = 1.0;
            lu.solve(&mut col);
            for i in 0..n {
                d[i * n + j] = col[i];
            }
        }
        Ok(Some(Regular {
            inner,
            s: s.to_vec(),
            d,
            n,
            buf: RefCell::new(vec![0.0; n]),
        }))
    }

    /// `out ← D out` (rows of `width` columns, `n` of them).
    #[allow(clippy::needless_range_loop)] // a matrix product over columns of `out`
    fn apply_d(&self, out: &mut [f64], width: usize) {
        let n = self.n;
        let mut buf = self.buf.borrow_mut();
        for c in 0..width {
            for i in 0..n {
                buf[i] = (0..n).map(|j| self.d[i * n + j] * out[j * width + c]).sum();
            }
            for i in 0..n {
                out[i * width + c] = buf[i];
            }
        }
    }
}

impl<P: Bvp + ?Sized> Bvp for Regular<'_, P> {
    fn dims(&self) -> Dims {
        self.inner.dims()
    }
    fn interval(&self) -> (f64, f64) {
        self.inner.interval()
    }
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], dz: &mut [f64]) {
        self.inner.rhs(s, z, p, dz);
        let n = self.n;
        if s == 0.0 {
            self.apply_d(dz, 1);
        } else {
            for (d, row) in dz.iter_mut().zip(self.s.chunks_exact(n)) {
                *d += row.iter().zip(z).map(|(a, b)| a * b).sum::<f64>() / s;
            }
        }
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], res: &mut [f64]) {
        self.inner.bc(za, zb, p, res)
    }
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        p: &[f64],
        dfdz: &mut [f64],
        dfdp: &mut [f64],
    ) -> bool {
        if !self.inner.rhs_jacobian(s, z, p, dfdz, dfdp) {
            return false;
        }
        let n = self.n;
        if s == 0.0 {
            self.apply_d(dfdz, n);
            let k = self.inner.dims().k;
            if k > 0 {
                self.apply_d(dfdp, k);
            }
        } else {
            for (d, v) in dfdz.iter_mut().zip(&self.s) {
                *d += v / s;
            }
        }
        true
    }
    fn bc_jacobian(
        &self,
        za: &[f64],
        zb: &[f64],
        p: &[f64],
        dga: &mut [f64],
        dgb: &mut [f64],
        dgp: &mut [f64],
    ) -> bool {
        self.inner.bc_jacobian(za, zb, p, dga, dgb, dgp)
    }
}
