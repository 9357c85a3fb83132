//! Fixed-size problems: states and parameters as arrays `[f64; N]`, `[f64; K]`.
//!
//! Small problems (the rods of this project have `N = 4`, `K ≤ 3`) are most naturally written
//! with arrays: the sizes are checked by the compiler, the right-hand side returns its value and
//! the optimizer sees the loop bounds. Implement [`FixedBvp`] and wrap the problem in [`Fixed`]
//! to hand it to any solver of this crate; [`Fixed`] implements [`Bvp`] by viewing the solvers'
//! slices as arrays (no copies of the state, no allocation).
//!
//! The solvers themselves are runtime-sized: they size their work buffers once per solver and
//! problem size, so neither kind of problem allocates in the Newton or integration loops
//! (`tests/allocations.rs` counts the allocations of whole solves).
//!
//! The boundary residual has `N + K` entries, a length stable Rust cannot yet spell as an array
//! type, so [`FixedBvp::bc`] and its Jacobian write into slices of that length.
//!
//! ```
//! use bvp::fixed::{Fixed, FixedBvp};
//! use bvp::{BvpSolver, Guess, Shooting, ShootingOptions};
//!
//! /// `y'' = −y`, `y(0) = 0`, `y(π/2) = 1`: `y = sin s`.
//! struct Sine;
//! impl FixedBvp<2, 0> for Sine {
//!     fn interval(&self) -> (f64, f64) {
//!         (0.0, std::f64::consts::FRAC_PI_2)
//!     }
//!     fn rhs(&self, _s: f64, z: &[f64; 2], _p: &[f64; 0]) -> [f64; 2] {
//!         [z[1], -z[0]]
//!     }
//!     fn bc(&self, za: &[f64; 2], zb: &[f64; 2], _p: &[f64; 0], res: &mut [f64]) {
//!         res[0] = za[0];
//!         res[1] = zb[0] - 1.0;
//!     }
//! }
//!
//! let guess = Guess::constant(0.0, std::f64::consts::FRAC_PI_2, 3, &[0.5, 0.5], vec![]);
//! let sol = Shooting::new(ShootingOptions::default())?.solve(&Fixed(Sine), &guess)?;
//! assert!((sol.node(0)[1] - 1.0).abs() < 1e-9); // y'(0) = cos 0
//! # Ok::<(), bvp::BvpError>(())
//! ```

use crate::{Bvp, Dims};

/// A boundary-value problem with `N` states and `K` unknown parameters, written with arrays.
///
/// Same problem as [`Bvp`]: `z' = F(s, z, p)` on `[a, b]`, `g(z(a), z(b), p) = 0` with `N + K`
/// conditions. Jacobians are optional (finite differences otherwise); matrices are row-major as
/// in [`Bvp`]: `dfdz[i][j] = ∂F_i/∂z_j`, `dfdp[i][j] = ∂F_i/∂p_j`.
pub trait FixedBvp<const N: usize, const K: usize> {
    /// The interval `[a, b]`, `a < b`.
    fn interval(&self) -> (f64, f64);
    /// Right-hand side `F(s, z, p)`.
    fn rhs(&self, s: f64, z: &[f64; N], p: &[f64; K]) -> [f64; N];
    /// Boundary residual `g(za, zb, p)` into `res` (length `N + K`).
    fn bc(&self, za: &[f64; N], zb: &[f64; N], p: &[f64; K], res: &mut [f64]);
    /// Analytic `(∂F/∂z, ∂F/∂p)`; `None` (the default) for finite differences.
    #[allow(clippy::type_complexity)]
    fn rhs_jacobian(
        &self,
        _s: f64,
        _z: &[f64; N],
        _p: &[f64; K],
    ) -> Option<([[f64; N]; N], [[f64; K]; N])> {
        None
    }
    /// Analytic Jacobians of `g` (row-major, `N + K` rows) as in [`Bvp::bc_jacobian`]; `false`
    /// (the default) for finite differences.
    fn bc_jacobian(
        &self,
        _za: &[f64; N],
        _zb: &[f64; N],
        _p: &[f64; K],
        _dga: &mut [f64],
        _dgb: &mut [f64],
        _dgp: &mut [f64],
    ) -> bool {
        false
    }
}

/// Adapter that makes a [`FixedBvp`] usable by every solver (it implements [`Bvp`]). The sizes
/// are inferred from the problem's one `FixedBvp` implementation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Fixed<T, const N: usize, const K: usize>(pub T);

/// Views the first `M` entries of a solver slice as an array. Solvers pass slices of exactly the
/// lengths [`Bvp::dims`] announces, so the view always exists.
fn view<const M: usize>(x: &[f64]) -> &[f64; M] {
    match x.first_chunk::<M>() {
        Some(a) => a,
        None => unreachable!("solver passed {} values, the problem has {M}", x.len()),
    }
}

impl<T: FixedBvp<N, K>, const N: usize, const K: usize> Bvp for Fixed<T, N, K> {
    fn dims(&self) -> Dims {
        Dims { n: N, k: K }
    }
    fn interval(&self) -> (f64, f64) {
        self.0.interval()
    }
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], dz: &mut [f64]) {
        dz[..N].copy_from_slice(&self.0.rhs(s, view(z), view(p)));
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], res: &mut [f64]) {
        self.0.bc(view(za), view(zb), view(p), res)
    }
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        p: &[f64],
        dfdz: &mut [f64],
        dfdp: &mut [f64],
    ) -> bool {
        match self.0.rhs_jacobian(s, view(z), view(p)) {
            Some((jz, jp)) => {
                for i in 0..N {
                    dfdz[i * N..(i + 1) * N].copy_from_slice(&jz[i]);
                    dfdp[i * K..(i + 1) * K].copy_from_slice(&jp[i]);
                }
                true
            }
            None => false,
        }
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
        self.0
            .bc_jacobian(view(za), view(zb), view(p), dga, dgb, dgp)
    }
}
