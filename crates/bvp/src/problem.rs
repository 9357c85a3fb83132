//! The problem definition.

/// Sizes of a problem: `n` states and `k` unknown parameters (so `n + k` boundary conditions).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Dims {
    /// Number of states `n`.
    pub n: usize,
    /// Number of unknown parameters `k`.
    pub k: usize,
}

/// A two-point boundary-value problem `z' = F(s, z, p)` on `[a, b]`, `g(z(a), z(b), p) = 0`.
///
/// # Jacobian layout (one convention for every Jacobian of the crate)
///
/// Every Jacobian is a row-major matrix `d[row][col] = ∂(output row)/∂(input col)`, here stored
/// flat as `d[row * cols + col]`:
///
/// | name   | rows (outputs)       | cols (inputs) | entry `[i * cols + j]` |
/// |--------|----------------------|---------------|------------------------|
/// | `dfdz` | `n` (components of F) | `n`          | `∂F_i/∂z_j`            |
/// | `dfdp` | `n`                  | `k`           | `∂F_i/∂p_j`            |
/// | `dga`  | `n + k` (conditions) | `n`           | `∂g_i/∂z_j(a)`         |
/// | `dgb`  | `n + k`              | `n`           | `∂g_i/∂z_j(b)`         |
/// | `dgp`  | `n + k`              | `k`           | `∂g_i/∂p_j`            |
///
/// Without parameters (`k = 0`) `dfdp` and `dgp` are empty and can be ignored.
/// [`crate::fixed::FixedBvp`] uses the same layout as arrays of rows (`d[i][j]`), and
/// [`crate::continuation::ParamBvp`] adds the `λ` columns `dfdl`, `dgl`.
/// A problem can also be assembled from closures with [`crate::from_fns`].
///
/// The Jacobian methods return `false` when not implemented (the default); solvers then use
/// finite differences ([`crate::fd`]; the collocation and shooting solvers difference the columns
/// of `∂F/∂z` in groups by the sparsity they learn at a solve's first Jacobian, one evaluation
/// per group instead of per column). Implementations must not allocate: solvers call these in
/// their inner loops. Non-finite output is detected by the solvers and reported as
/// [`crate::BvpError::NonFinite`].
///
/// ```
/// use bvp::{Bvp, BvpSolver, Dims, Guess, Shooting, ShootingOptions};
///
/// /// y'' = −y, y(0) = 0, y(π/2) = 1: y = sin s (z = (y, y')).
/// struct Sine;
/// impl Bvp for Sine {
///     fn dims(&self) -> Dims {
///         Dims { n: 2, k: 0 }
///     }
///     fn interval(&self) -> (f64, f64) {
///         (0.0, std::f64::consts::FRAC_PI_2)
///     }
///     fn rhs(&self, _s: f64, z: &[f64], _p: &[f64], dz: &mut [f64]) {
///         dz[0] = z[1];
///         dz[1] = -z[0];
///     }
///     fn bc(&self, za: &[f64], zb: &[f64], _p: &[f64], res: &mut [f64]) {
///         res[0] = za[0];
///         res[1] = zb[0] - 1.0;
///     }
/// }
/// let guess = Guess::constant(0.0, std::f64::consts::FRAC_PI_2, 5, &[0.5, 0.5], vec![]);
/// let sol = Shooting::new(ShootingOptions::default())?.solve(&Sine, &guess)?;
/// assert!((sol.at(0.5)[0] - 0.5f64.sin()).abs() < 1e-8);
/// # Ok::<(), bvp::BvpError>(())
/// ```
pub trait Bvp {
    /// Number of states and unknown parameters.
    fn dims(&self) -> Dims;
    /// The interval `[a, b]`, `a < b`.
    fn interval(&self) -> (f64, f64);
    /// Right-hand side: writes `F(s, z, p)` into `dz`.
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], dz: &mut [f64]);
    /// Boundary residual: writes `g(za, zb, p)` (length `n + k`) into `res`.
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], res: &mut [f64]);
    /// Analytic `dfdz = ∂F/∂z` (n×n) and `dfdp = ∂F/∂p` (n×k), row-major; `false` if not provided.
    fn rhs_jacobian(
        &self,
        _s: f64,
        _z: &[f64],
        _p: &[f64],
        _dfdz: &mut [f64],
        _dfdp: &mut [f64],
    ) -> bool {
        false
    }
    /// Analytic Jacobians of `g` (row-major, `n + k` rows): `dga = ∂g/∂z(a)`, `dgb = ∂g/∂z(b)`,
    /// `dgp = ∂g/∂p`; `false` if not provided.
    fn bc_jacobian(
        &self,
        _za: &[f64],
        _zb: &[f64],
        _p: &[f64],
        _dga: &mut [f64],
        _dgb: &mut [f64],
        _dgp: &mut [f64],
    ) -> bool {
        false
    }
    /// A singular term: the `n × n` matrix `S` (row-major) of
    /// `z' = S z / s + F(s, z, p)` on `[0, b]` (radially symmetric problems: Lane–Emden,
    /// cylindrical and spherical diffusion), `rhs` writing `F` alone. Default `None`.
    ///
    /// The solvers handle `s = 0` as scipy's `solve_bvp` does: a solution regular there has
    /// `S z(0) = 0` (state it among the boundary conditions, e.g. `y'(0) = 0`) and
    /// `z'(0) = (I − S)⁻¹ F(0, z(0), p)`, which collocation uses at the node `s = 0`; shooting
    /// starts from that series, `z(δ) = z(0) + δ z'(0)` with `δ = 1e-7 b` (error `O(δ²)`). The
    /// interval must start at `a = 0` and `I − S` be invertible, else
    /// [`crate::BvpError::InvalidOption`].
    fn singular_term(&self) -> Option<&[f64]> {
        None
    }
}

impl<T: Bvp + ?Sized> Bvp for &T {
    fn dims(&self) -> Dims {
        (**self).dims()
    }
    fn interval(&self) -> (f64, f64) {
        (**self).interval()
    }
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], dz: &mut [f64]) {
        (**self).rhs(s, z, p, dz)
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], res: &mut [f64]) {
        (**self).bc(za, zb, p, res)
    }
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        p: &[f64],
        dfdz: &mut [f64],
        dfdp: &mut [f64],
    ) -> bool {
        (**self).rhs_jacobian(s, z, p, dfdz, dfdp)
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
        (**self).bc_jacobian(za, zb, p, dga, dgb, dgp)
    }
    fn singular_term(&self) -> Option<&[f64]> {
        (**self).singular_term()
    }
}

/// Signature of an unset rhs Jacobian closure of [`FnBvp`].
pub type NoRhsJacobian = fn(f64, &[f64], &[f64], &mut [f64], &mut [f64]);
/// Signature of an unset bc Jacobian closure of [`FnBvp`].
pub type NoBcJacobian = fn(&[f64], &[f64], &[f64], &mut [f64], &mut [f64], &mut [f64]);

/// A problem assembled from closures, made by [`from_fns`]; implements [`Bvp`].
///
/// The closures take the arguments of the [`Bvp`] methods of the same names (Jacobian layouts as
/// documented there). Parameters default to none; Jacobians default to finite differences.
///
/// ```
/// use bvp::{from_fns, BvpSolver, Collocation, CollocationOptions, Guess};
///
/// // y'' = −y, y(0) = 0, y(π/2) = 1: y = sin s.
/// let sine = from_fns(
///     2,
///     (0.0, std::f64::consts::FRAC_PI_2),
///     |_s, z, _p, dz| {
///         dz[0] = z[1];
///         dz[1] = -z[0];
///     },
///     |za, zb, _p, res| {
///         res[0] = za[0];
///         res[1] = zb[0] - 1.0;
///     },
/// )
/// .with_rhs_jacobian(|_s, _z, _p, dfdz, _dfdp| dfdz.copy_from_slice(&[0.0, 1.0, -1.0, 0.0]));
/// let guess = Guess::constant(0.0, std::f64::consts::FRAC_PI_2, 11, &[0.5, 0.5], vec![]);
/// let sol = Collocation::new(CollocationOptions::default())?.solve(&sine, &guess)?;
/// assert!((sol.node(0)[1] - 1.0).abs() < 1e-6); // y'(0) = cos 0
/// # Ok::<(), bvp::BvpError>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct FnBvp<F, G, J = NoRhsJacobian, H = NoBcJacobian> {
    dims: Dims,
    interval: (f64, f64),
    rhs: F,
    bc: G,
    rhs_jac: Option<J>,
    bc_jac: Option<H>,
}

/// A problem with `n` states on `interval = (a, b)` from its right-hand side
/// `rhs(s, z, p, dz)` and boundary residual `bc(za, zb, p, res)`; see [`FnBvp`] for parameters
/// and Jacobians.
pub fn from_fns<F, G>(n: usize, interval: (f64, f64), rhs: F, bc: G) -> FnBvp<F, G>
where
    F: Fn(f64, &[f64], &[f64], &mut [f64]),
    G: Fn(&[f64], &[f64], &[f64], &mut [f64]),
{
    FnBvp {
        dims: Dims { n, k: 0 },
        interval,
        rhs,
        bc,
        rhs_jac: None,
        bc_jac: None,
    }
}

impl<F, G, J, H> FnBvp<F, G, J, H> {
    /// The same problem with `k` unknown parameters (so `bc` writes `n + k` residuals).
    pub fn with_params(mut self, k: usize) -> Self {
        self.dims.k = k;
        self
    }

    /// The same problem with the analytic `jac(s, z, p, dfdz, dfdp)`.
    pub fn with_rhs_jacobian<J2>(self, jac: J2) -> FnBvp<F, G, J2, H>
    where
        J2: Fn(f64, &[f64], &[f64], &mut [f64], &mut [f64]),
    {
        FnBvp {
            dims: self.dims,
            interval: self.interval,
            rhs: self.rhs,
            bc: self.bc,
            rhs_jac: Some(jac),
            bc_jac: self.bc_jac,
        }
    }

    /// The same problem with the analytic `jac(za, zb, p, dga, dgb, dgp)`.
    pub fn with_bc_jacobian<H2>(self, jac: H2) -> FnBvp<F, G, J, H2>
    where
        H2: Fn(&[f64], &[f64], &[f64], &mut [f64], &mut [f64], &mut [f64]),
    {
        FnBvp {
            dims: self.dims,
            interval: self.interval,
            rhs: self.rhs,
            bc: self.bc,
            rhs_jac: self.rhs_jac,
            bc_jac: Some(jac),
        }
    }
}

impl<F, G, J, H> Bvp for FnBvp<F, G, J, H>
where
    F: Fn(f64, &[f64], &[f64], &mut [f64]),
    G: Fn(&[f64], &[f64], &[f64], &mut [f64]),
    J: Fn(f64, &[f64], &[f64], &mut [f64], &mut [f64]),
    H: Fn(&[f64], &[f64], &[f64], &mut [f64], &mut [f64], &mut [f64]),
{
    fn dims(&self) -> Dims {
        self.dims
    }
    fn interval(&self) -> (f64, f64) {
        self.interval
    }
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], dz: &mut [f64]) {
        (self.rhs)(s, z, p, dz)
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], res: &mut [f64]) {
        (self.bc)(za, zb, p, res)
    }
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        p: &[f64],
        dfdz: &mut [f64],
        dfdp: &mut [f64],
    ) -> bool {
        match &self.rhs_jac {
            Some(j) => {
                j(s, z, p, dfdz, dfdp);
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
        match &self.bc_jac {
            Some(j) => {
                j(za, zb, p, dga, dgb, dgp);
                true
            }
            None => false,
        }
    }
}

/// A problem with a singular term: `z' = S z / s + F(s, z, p)` on `[0, b]`, with `F`, the
/// boundary conditions and their Jacobians those of `problem` and `S` (row-major `n × n`)
/// reported by [`Bvp::singular_term`] (see there for how the solvers treat `s = 0`).
///
/// ```
/// use bvp::{from_fns, BvpSolver, Collocation, CollocationOptions, Guess, SingularTerm};
///
/// // Lane–Emden of index 5: y'' + (2/x) y' + y⁵ = 0, y'(0) = 0, y(1) = √(3/4):
/// // y = (1 + x²/3)^(−1/2). With z = (y, y'): z' = S z / x + (y', −y⁵), S = [0 0; 0 −2].
/// let f = from_fns(
///     2,
///     (0.0, 1.0),
///     |_x, z, _p, dz| {
///         dz[0] = z[1];
///         dz[1] = -z[0].powi(5);
///     },
///     |za, zb, _p, r| {
///         r[0] = za[1];
///         r[1] = zb[0] - 0.75_f64.sqrt();
///     },
/// );
/// let p = SingularTerm::new(f, vec![0.0, 0.0, 0.0, -2.0]);
/// let guess = Guess::constant(0.0, 1.0, 11, &[1.0, 0.0], vec![]);
/// let sol = Collocation::new(CollocationOptions::default())?.solve(&p, &guess)?;
/// assert!((sol.at(0.0)[0] - 1.0).abs() < 1e-6);
/// # Ok::<(), bvp::BvpError>(())
/// ```
#[derive(Clone, Debug)]
pub struct SingularTerm<P> {
    problem: P,
    s: Vec<f64>,
}

impl<P> SingularTerm<P> {
    /// `problem` with the singular term `S z / s`, `s_matrix` row-major `n × n`.
    pub fn new(problem: P, s_matrix: Vec<f64>) -> Self {
        SingularTerm {
            problem,
            s: s_matrix,
        }
    }

    /// The problem without the term.
    pub fn inner(&self) -> &P {
        &self.problem
    }
}

impl<P: Bvp> Bvp for SingularTerm<P> {
    fn dims(&self) -> Dims {
        self.problem.dims()
    }
    fn interval(&self) -> (f64, f64) {
        self.problem.interval()
    }
    fn rhs(&self, s: f64, z: &[f64], p: &[f64], dz: &mut [f64]) {
        self.problem.rhs(s, z, p, dz)
    }
    fn bc(&self, za: &[f64], zb: &[f64], p: &[f64], res: &mut [f64]) {
        self.problem.bc(za, zb, p, res)
    }
    fn rhs_jacobian(
        &self,
        s: f64,
        z: &[f64],
        p: &[f64],
        dfdz: &mut [f64],
        dfdp: &mut [f64],
    ) -> bool {
        self.problem.rhs_jacobian(s, z, p, dfdz, dfdp)
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
        self.problem.bc_jacobian(za, zb, p, dga, dgb, dgp)
    }
    fn singular_term(&self) -> Option<&[f64]> {
        Some(&self.s)
    }
}
