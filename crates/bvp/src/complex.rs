//! Complex problems: `z' = F(s, z, p)` with `z ∈ Cⁿ`, `p ∈ Cᵏ`, solved by every solver through
//! [`Split`], which presents them as the real problem of their real and imaginary parts.
//!
//! # Layout
//!
//! Real states are interleaved: complex state `j` is real states `2j` (real part) and `2j + 1`
//! (imaginary part); likewise the parameters and the `n + k` complex boundary conditions. A
//! guess is built with [`Split::guess`]; [`Split::complex`] reads complex values back from any
//! real vector of the solution (`Solution::at`, `node`, `params`). The Jacobians of the split
//! problem are finite differences (one per real component), so a holomorphic `F` costs two
//! evaluations per complex state, as doubling the system by hand would.
//!
//! ```
//! use bvp::complex::{Complex64, ComplexBvp, Split};
//! use bvp::{BvpSolver, Collocation, CollocationOptions, Dims};
//!
//! // y'' = y, y(0) = 1 + i, y(1) = 0 (scipy's `test_complex`).
//! struct Exp;
//! impl ComplexBvp for Exp {
//!     fn dims(&self) -> Dims {
//!         Dims { n: 2, k: 0 }
//!     }
//!     fn interval(&self) -> (f64, f64) {
//!         (0.0, 1.0)
//!     }
//!     fn rhs(&self, _s: f64, z: &[Complex64], _p: &[Complex64], dz: &mut [Complex64]) {
//!         dz[0] = z[1];
//!         dz[1] = z[0];
//!     }
//!     fn bc(&self, za: &[Complex64], zb: &[Complex64], _p: &[Complex64], r: &mut [Complex64]) {
//!         r[0] = za[0] - Complex64::new(1.0, 1.0);
//!         r[1] = zb[0];
//!     }
//! }
//! let p = Split::new(Exp);
//! let guess = p.guess(vec![0.0, 0.5, 1.0], vec![], |_s, z| z.fill(Complex64::new(0.0, 0.0)));
//! let sol = Collocation::new(CollocationOptions::default())?.solve(&p, &guess)?;
//! let y0 = p.complex(&sol.at(0.0))[0];
//! assert!((y0 - Complex64::new(1.0, 1.0)).norm() < 1e-9);
//! # Ok::<(), bvp::BvpError>(())
//! ```

use crate::{Bvp, Dims, Guess};
pub use num_complex::Complex64;
use std::cell::RefCell;

/// A complex two-point BVP (see the [module docs](self)); `n` complex states, `k` complex
/// parameters, `n + k` complex boundary conditions.
pub trait ComplexBvp {
    /// Complex states `n` and parameters `k`.
    fn dims(&self) -> Dims;
    /// The real interval `[a, b]`.
    fn interval(&self) -> (f64, f64);
    /// Writes `F(s, z, p)` into `dz`.
    fn rhs(&self, s: f64, z: &[Complex64], p: &[Complex64], dz: &mut [Complex64]);
    /// Writes the `n + k` boundary residuals into `res`.
    fn bc(&self, za: &[Complex64], zb: &[Complex64], p: &[Complex64], res: &mut [Complex64]);
}

/// Work vectors of [`Split`] (complex copies of the real arguments).
#[derive(Debug, Default)]
struct Buffers {
    za: Vec<Complex64>,
    zb: Vec<Complex64>,
    p: Vec<Complex64>,
    out: Vec<Complex64>,
}

/// A [`ComplexBvp`] as the real [`Bvp`] of its real and imaginary parts (`2n` states, `2k`
/// parameters, interleaved).
#[derive(Debug)]
pub struct Split<P> {
    problem: P,
    buf: RefCell<Buffers>,
}

fn to_complex(x: &[f64], out: &mut Vec<Complex64>) {
    out.clear();
    out.extend(x.chunks_exact(2).map(|c| Complex64::new(c[0], c[1])));
}

fn to_real(x: &[Complex64], out: &mut [f64]) {
    for (o, c) in out.chunks_exact_mut(2).zip(x) {
        o[0] = c.re;
        o[1] = c.im;
    }
}

impl<P: ComplexBvp> Split<P> {
    /// The real view of `problem`.
    pub fn new(problem: P) -> Self {
        Split {
            problem,
            buf: RefCell::new(Buffers::default()),
        }
    }

    /// The complex problem.
    pub fn inner(&self) -> &P {
        &self.problem
    }

    /// Complex values of a real vector of this problem (states or parameters).
    pub fn complex(&self, x: &[f64]) -> Vec<Complex64> {
        let mut out = Vec::new();
        to_complex(x, &mut out);
        out
    }

    /// A guess sampling the complex `f(s, z)` on `mesh`, with complex parameters `params`.
    pub fn guess(
        &self,
        mesh: Vec<f64>,
        params: Vec<Complex64>,
        mut f: impl FnMut(f64, &mut [Complex64]),
    ) -> Guess {
        let n = self.problem.dims().n;
        let mut zc = vec![Complex64::new(0.0, 0.0); n];
        let mut p = vec![0.0; 2 * params.len()];
        to_real(&params, &mut p);
        Guess::from_fn(2 * n, mesh, p, |s, z| {
            f(s, &mut zc);
            to_real(&zc, z);
        })
    }
}

impl<P: ComplexBvp> Bvp for Split<P> {
    fn dims(&self) -> Dims {
        let Dims { n, k } = self.problem.dims();
        Dims { n: 2 * n, k: 2 * k }
    }
    fn interval(&self) -> (f64, f64) {
        self.problem.interval()
    }
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], dz: &mut [f64]) {
        let mut b = self.buf.borrow_mut();
        let Buffers { za, p: pc, out, .. } = &mut *b;
        to_complex(z, za);
        to_complex(p, pc);
        out.clear();
        out.resize(za.len(), Complex64::new(0.0, 0.0));
        self.problem.rhs(s, za, pc, out);
        to_real(out, dz);
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], res: &mut [f64]) {
        let mut b = self.buf.borrow_mut();
        let Buffers {
            za: ca,
            zb: cb,
            p: pc,
            out,
        } = &mut *b;
        to_complex(za, ca);
        to_complex(zb, cb);
        to_complex(p, pc);
        out.clear();
        out.resize(res.len() / 2, Complex64::new(0.0, 0.0));
        self.problem.bc(ca, cb, pc, out);
        to_real(out, res);
    }
}
