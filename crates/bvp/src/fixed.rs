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
//! type, so [`FixedBvp::bc`] writes into a slice of that length, and the boundary Jacobians are
//! slices of `N + K` rows. Every Jacobian is written row by row, `d[i][j] = ∂(output i)/∂(input
//! j)` — the layout of [`Bvp`] (there flattened). The Jacobians in the parameters have methods
//! of their own ([`FixedBvp::rhs_param_jacobian`], [`FixedBvp::bc_param_jacobian`]).
//!
//! A problem without parameters implements [`SimpleBvp`] instead: no parameter arguments at
//! all, and `N` boundary conditions returned as an array. Every [`SimpleBvp`] is a
//! [`FixedBvp`] with `K = 0`, so it is wrapped in [`Fixed`] the same way.
//!
//! ```
//! use bvp::fixed::{Fixed, SimpleBvp};
//! use bvp::{BvpSolver, Guess, Shooting, ShootingOptions};
//!
//! /// `y'' = −y`, `y(0) = 0`, `y(π/2) = 1`: `y = sin s`.
//! struct Sine;
//! impl SimpleBvp<2> for Sine {
//!     fn interval(&self) -> (f64, f64) {
//!         (0.0, std::f64::consts::FRAC_PI_2)
//!     }
//!     fn rhs(&self, _s: f64, z: &[f64; 2]) -> [f64; 2] {
//!         [z[1], -z[0]]
//!     }
//!     fn bc(&self, za: &[f64; 2], zb: &[f64; 2]) -> [f64; 2] {
//!         [za[0], zb[0] - 1.0]
//!     }
//!     fn rhs_jacobian(&self, _s: f64, _z: &[f64; 2], dfdz: &mut [[f64; 2]; 2]) -> bool {
//!         *dfdz = [[0.0, 1.0], [-1.0, 0.0]];
//!         true
//!     }
//! }
//!
//! let guess = Guess::constant(0.0, std::f64::consts::FRAC_PI_2, 3, &[0.5, 0.5], vec![]);
//! let sol = Shooting::new(ShootingOptions::default())?.solve(&Fixed(Sine), &guess)?;
//! assert!((sol.node(0)[1] - 1.0).abs() < 1e-9); // y'(0) = cos 0
//! # Ok::<(), bvp::BvpError>(())
//! ```

use crate::{Bvp, Dims};

/// A boundary-value problem with `N` states and `K` unknown parameters (default none), written
/// with arrays.
///
/// Same problem as [`Bvp`]: `z' = F(s, z, p)` on `[a, b]`, `g(z(a), z(b), p) = 0` with `N + K`
/// conditions. Jacobians are optional (finite differences otherwise) and written row by row as
/// in [`Bvp`]: `dfdz[i][j] = ∂F_i/∂z_j`, `dfdp[i][j] = ∂F_i/∂p_j`, `dga[i][j] = ∂g_i/∂z_j(a)`,
/// `dgb[i][j] = ∂g_i/∂z_j(b)`, `dgp[i][j] = ∂g_i/∂p_j` (`i` over the `N + K` conditions).
///
/// The parameter Jacobians are asked for only when `K > 0`. An analytic Jacobian of `F` (or of
/// `g`) is used when every part of it is provided; with `K > 0` and no parameter part, the
/// solvers take finite differences of the whole of it.
pub trait FixedBvp<const N: usize, const K: usize = 0> {
    /// The interval `[a, b]`, `a < b`.
    fn interval(&self) -> (f64, f64);
    /// Right-hand side `F(s, z, p)`.
    fn rhs(&self, s: f64, z: &[f64; N], p: &[f64; K]) -> [f64; N];
    /// Boundary residual `g(za, zb, p)` into `res` (length `N + K`).
    fn bc(&self, za: &[f64; N], zb: &[f64; N], p: &[f64; K], res: &mut [f64]);
    /// Analytic `dfdz = ∂F/∂z`; `false` (the default) for finite differences.
    fn rhs_jacobian(
        &self,
        _s: f64,
        _z: &[f64; N],
        _p: &[f64; K],
        _dfdz: &mut [[f64; N]; N],
    ) -> bool {
        false
    }
    /// Analytic `dfdp = ∂F/∂p` (only asked for when `K > 0`); `false` (the default) for finite
    /// differences.
    fn rhs_param_jacobian(
        &self,
        _s: f64,
        _z: &[f64; N],
        _p: &[f64; K],
        _dfdp: &mut [[f64; K]; N],
    ) -> bool {
        false
    }
    /// Analytic `dga = ∂g/∂z(a)`, `dgb = ∂g/∂z(b)` (`N + K` rows each); `false` (the default)
    /// for finite differences.
    fn bc_jacobian(
        &self,
        _za: &[f64; N],
        _zb: &[f64; N],
        _p: &[f64; K],
        _dga: &mut [[f64; N]],
        _dgb: &mut [[f64; N]],
    ) -> bool {
        false
    }
    /// Analytic `dgp = ∂g/∂p` (`N + K` rows; only asked for when `K > 0`); `false` (the
    /// default) for finite differences.
    fn bc_param_jacobian(
        &self,
        _za: &[f64; N],
        _zb: &[f64; N],
        _p: &[f64; K],
        _dgp: &mut [[f64; K]],
    ) -> bool {
        false
    }
}

/// A boundary-value problem with `N` states and no unknown parameters, written with arrays:
/// `z' = F(s, z)` on `[a, b]`, `g(z(a), z(b)) = 0` with `N` conditions. Jacobians are optional
/// (finite differences otherwise), row by row: `dfdz[i][j] = ∂F_i/∂z_j`,
/// `dga[i][j] = ∂g_i/∂z_j(a)`, `dgb[i][j] = ∂g_i/∂z_j(b)`. Every `SimpleBvp<N>` is a
/// [`FixedBvp<N>`](FixedBvp); wrap it in [`Fixed`] for the solvers.
pub trait SimpleBvp<const N: usize> {
    /// The interval `[a, b]`, `a < b`.
    fn interval(&self) -> (f64, f64);
    /// Right-hand side `F(s, z)`.
    fn rhs(&self, s: f64, z: &[f64; N]) -> [f64; N];
    /// Boundary residual `g(za, zb)`.
    fn bc(&self, za: &[f64; N], zb: &[f64; N]) -> [f64; N];
    /// Analytic `dfdz = ∂F/∂z`; `false` (the default) for finite differences.
    fn rhs_jacobian(&self, _s: f64, _z: &[f64; N], _dfdz: &mut [[f64; N]; N]) -> bool {
        false
    }
    /// Analytic `dga = ∂g/∂z(a)`, `dgb = ∂g/∂z(b)`; `false` (the default) for finite differences.
    fn bc_jacobian(
        &self,
        _za: &[f64; N],
        _zb: &[f64; N],
        _dga: &mut [[f64; N]; N],
        _dgb: &mut [[f64; N]; N],
    ) -> bool {
        false
    }
}

impl<T: SimpleBvp<N>, const N: usize> FixedBvp<N> for T {
    fn interval(&self) -> (f64, f64) {
        SimpleBvp::interval(self)
    }
    fn rhs(&self, s: f64, z: &[f64; N], _p: &[f64; 0]) -> [f64; N] {
        SimpleBvp::rhs(self, s, z)
    }
    fn bc(&self, za: &[f64; N], zb: &[f64; N], _p: &[f64; 0], res: &mut [f64]) {
        res[..N].copy_from_slice(&SimpleBvp::bc(self, za, zb));
    }
    fn rhs_jacobian(&self, s: f64, z: &[f64; N], _p: &[f64; 0], dfdz: &mut [[f64; N]; N]) -> bool {
        SimpleBvp::rhs_jacobian(self, s, z, dfdz)
    }
    fn bc_jacobian(
        &self,
        za: &[f64; N],
        zb: &[f64; N],
        _p: &[f64; 0],
        dga: &mut [[f64; N]],
        dgb: &mut [[f64; N]],
    ) -> bool {
        // the solvers pass N + K = N rows
        match (
            <&mut [[f64; N]; N]>::try_from(dga),
            <&mut [[f64; N]; N]>::try_from(dgb),
        ) {
            (Ok(a), Ok(b)) => SimpleBvp::bc_jacobian(self, za, zb, a, b),
            _ => false,
        }
    }
}

/// Adapter that makes a [`FixedBvp`] usable by every solver (it implements [`Bvp`]). The sizes
/// are inferred from the problem's one `FixedBvp` implementation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Fixed<T, const N: usize, const K: usize = 0>(pub T);

/// Views the first `M` entries of a solver slice as an array. Solvers pass slices of exactly the
/// lengths [`Bvp::dims`] announces, so the view always exists.
fn view<const M: usize>(x: &[f64]) -> &[f64; M] {
    match x.first_chunk::<M>() {
        Some(a) => a,
        None => unreachable!("solver passed {} values, the problem has {M}", x.len()),
    }
}

/// Views the first `rows · M` entries of a flat row-major matrix as `rows` rows of `M` columns.
fn rows_mut<const M: usize>(x: &mut [f64], rows: usize) -> &mut [[f64; M]] {
    assert!(
        x.len() >= rows * M,
        "matrix of {rows}×{M} in {} values",
        x.len()
    );
    // SAFETY: `[f64; M]` is `M` consecutive `f64` with the alignment of `f64`; the view covers the
    // first `rows · M` values of `x` (checked above; nothing for `M = 0`) and borrows `x`
    // exclusively for its lifetime.
    unsafe { std::slice::from_raw_parts_mut(x.as_mut_ptr().cast::<[f64; M]>(), rows) }
}

/// Views a flat row-major `R × C` matrix as an array of rows.
fn matrix_mut<const R: usize, const C: usize>(x: &mut [f64]) -> &mut [[f64; C]; R] {
    match rows_mut::<C>(x, R).try_into() {
        Ok(m) => m,
        Err(_) => unreachable!("a slice of {R} rows is an array of {R} rows"),
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
        let (z, p) = (view(z), view(p));
        self.0.rhs_jacobian(s, z, p, matrix_mut(dfdz))
            && (K == 0 || self.0.rhs_param_jacobian(s, z, p, matrix_mut(dfdp)))
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
        let (za, zb, p) = (view(za), view(zb), view(p));
        self.0
            .bc_jacobian(za, zb, p, rows_mut(dga, N + K), rows_mut(dgb, N + K))
            && (K == 0 || self.0.bc_param_jacobian(za, zb, p, rows_mut(dgp, N + K)))
    }
}
